// SPDX-License-Identifier: MIT
// The C++ side of the Python call-overhead comparison (bench/python/run_overhead.sh): serves
// ElasticBody::solve and ShapeOracle::evaluate_design on a case, one call per request, with
// exactly the call sequence bench/python/overhead.py makes through the module, and answers
// each request with the call's wall time and process CPU time. The driver alternates one C++ call and the same Python
// call, so both sides see the same machine load (the shared build machine's load moves the
// absolute times by tens of percent within a minute). Plain std::chrono rather than Google
// Benchmark: both sides must time the same calls in the same order (the contact solver
// warm-starts from the previous solve).
//
//   python_overhead_bench CASE.toml       then lines "solve K", "oracle K", "cached" on stdin
#include <Eigen/Core>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>

#include "frictopt/io/case_file.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/shape_oracle.hpp"

int main(int argc, char** argv) {
  using namespace frictopt;
  using Clock = std::chrono::steady_clock;
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s CASE.toml < requests\n", argv[0]);
    return 2;
  }
  const io::CaseDescription description = io::load_case(argv[1]);
  const Eigen::VectorXd alpha0 = description.body.initial_design;
  study::ElasticBody body(description.body);
  (void)body.solve(alpha0);  // warm-up, as the Python side
  study::ElasticBody oracle_body(description.body);
  study::ShapeOracle oracle(oracle_body, description.required_cost());
  (void)oracle.evaluate_design(alpha0, true);
  std::printf("ready\n");
  std::fflush(stdout);

  for (std::string line; std::getline(std::cin, line);) {
    std::istringstream request(line);
    std::string what;
    int k = 0;
    request >> what >> k;
    bool ok = true;
    const auto start = Clock::now();
    const std::clock_t cpu_start = std::clock();  // process CPU time: robust to the machine's load
    if (what == "solve") {
      // Body.solve: alternating α⁰ and 1.001·α⁰.
      const Eigen::VectorXd alpha = k % 2 ? Eigen::VectorXd(1.001 * alpha0) : alpha0;
      ok = body.solve(alpha).summary.status == Status::kConverged;
    } else if (what == "oracle") {
      // Θ and ξ at the distinct designs (1 + 1e-4·k)·α⁰ (no cache hits).
      const Eigen::VectorXd alpha = (1.0 + 1e-4 * k) * alpha0;
      ok = oracle.evaluate_design(alpha, true).ok;
    } else if (what == "cached") {
      // A cached evaluation and the copy the binding returns: the call's fixed cost.
      const study::Evaluation copy = oracle.evaluate_design(alpha0, true);
      ok = copy.ok;
    } else {
      return 2;
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    const double cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    if (!ok) return 3;
    std::printf("%.9e %.9e\n", seconds, cpu_seconds);
    std::fflush(stdout);
  }
  return 0;
}
