// SPDX-License-Identifier: MIT
// The bundle trust of commit 47d6906 (fixed step bound, absolute stopping test) on the current
// Lukšan–Vlček set: per problem "name|f|relative error|evaluations|iterations|status" and a
// SUMMARY line. Built and run by measure_previous.sh (not part of the CMake build: it compiles
// against the old optim sources).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>
#include "frictopt/optim/bundle_trust.hpp"
#include "testset/luksan_vlcek.hpp"
namespace fo = frictopt::optim;
int main(int argc, char** argv) {
  fo::BundleTrust::Options bt;
  bt.keep_history = false;
  if (argc > 1) { bt.max_iterations = 3000; bt.max_evaluations = 10000; }
  std::vector<fo::LuksanVlcekProblem> problems = fo::luksan_vlcek_unconstrained();
  for (auto set : {fo::luksan_vlcek_constrained(), fo::luksan_vlcek_scaled_variants()})
    problems.insert(problems.end(), set.begin(), set.end());
  std::vector<int> ev, evo; int solved = 0, falsec = 0, solved_o = 0;
  for (const auto& p : problems) {
    fo::FunctionOracle oracle(p.evaluate);
    const auto s = fo::BundleTrust(bt, p.constraints).minimize(oracle, p.x0);
    const bool ok = p.solved(s.f, 1e-4);
    solved += ok; falsec += s.converged() && !ok;
    ev.push_back(s.evaluations);
    const bool orig = p.name.find('*') == std::string::npos;
    if (orig) { evo.push_back(s.evaluations); solved_o += ok; }
    std::printf("%s|%.8g|%.1e|%d|%d|%s\n", p.name.c_str(), s.f, p.relative_error(s.f), s.evaluations, s.iterations,
                std::string(frictopt::to_string(s.status)).c_str());
  }
  auto med = [](std::vector<int> v) { std::sort(v.begin(), v.end()); size_t m = v.size()/2; return v.size()%2 ? v[m] : 0.5*(v[m-1]+v[m]); };
  std::printf("SUMMARY solved %d of %zu (originals %d of %zu), false converged %d, median evals all %.1f originals %.1f\n",
              solved, problems.size(), solved_o, evo.size(), falsec, med(ev), med(evo));
}
