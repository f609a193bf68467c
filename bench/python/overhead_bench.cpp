// SPDX-License-Identifier: MIT
// The C++ side of the Python call-overhead comparison (bench/python/run_overhead.sh): times
// ElasticBody::solve and ShapeOracle::evaluate_design on the demo case with exactly the call
// sequence bench/python/overhead.py makes through the module, and prints the per-call times as
// JSON. Plain std::chrono rather than Google Benchmark so that both sides time the same calls
// in the same order (the contact solver warm-starts from the previous solve).
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "frictopt/io/case_file.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace frictopt;
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s CASE.toml REPETITIONS\n", argv[0]);
    return 2;
  }
  const io::CaseDescription description = io::load_case(argv[1]);
  const int repetitions = std::atoi(argv[2]);
  const Eigen::VectorXd alpha0 = description.body.initial_design;

  // Body.solve: warm-up at α⁰, then `repetitions` solves alternating α⁰ and 1.001·α⁰.
  study::ElasticBody body(description.body);
  (void)body.solve(alpha0);
  std::vector<double> solve_times;
  for (int k = 0; k < repetitions; ++k) {
    const Eigen::VectorXd alpha = k % 2 ? Eigen::VectorXd(1.001 * alpha0) : alpha0;
    const auto start = Clock::now();
    const study::BodyState state = body.solve(alpha);
    solve_times.push_back(seconds_since(start));
    if (state.summary.status != Status::kConverged) return 3;
  }

  // Oracle: Θ and ξ at distinct designs (1 + 1e-4·k)·α⁰ (no cache hits), after α⁰.
  study::ElasticBody oracle_body(description.body);
  study::ShapeOracle oracle(oracle_body, description.required_cost());
  (void)oracle.evaluate_design(alpha0, true);
  std::vector<double> oracle_times;
  for (int k = 1; k <= repetitions; ++k) {
    const Eigen::VectorXd alpha = (1.0 + 1e-4 * k) * alpha0;
    const auto start = Clock::now();
    const study::Evaluation& e = oracle.evaluate_design(alpha, true);
    oracle_times.push_back(seconds_since(start));
    if (!e.ok) return 3;
  }
  // A cached evaluation: the call's fixed cost without a solve (the Python side adds its own).
  std::vector<double> cached_times;
  for (int k = 0; k < 1000; ++k) {
    const auto start = Clock::now();
    const study::Evaluation& e = oracle.evaluate_design(alpha0, true);
    const study::Evaluation copy = e;  // the binding returns a copy
    cached_times.push_back(seconds_since(start));
    if (!copy.ok) return 3;
  }

  io::JsonValue json = io::JsonValue::object();
  json["solve_seconds"] = Eigen::VectorXd(Eigen::Map<Eigen::VectorXd>(solve_times.data(), repetitions));
  json["oracle_seconds"] = Eigen::VectorXd(Eigen::Map<Eigen::VectorXd>(oracle_times.data(), repetitions));
  json["cached_oracle_seconds"] = Eigen::VectorXd(Eigen::Map<Eigen::VectorXd>(cached_times.data(), 1000));
  std::printf("%s\n", io::to_json_string(json, -1).c_str());
  return 0;
}
