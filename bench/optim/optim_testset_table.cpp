// SPDX-License-Identifier: MIT
// Prints the Markdown table of docs/optim-testset.md: every implemented Lukšan–Vlček problem
// solved by BundleTrust with default options (ε = 1e-4; only the limits are raised) and by the projected
// subgradient baseline with the same evaluation budget.
//   build-optim/bench/optim/optim_testset_table > table.md
#include <cmath>
#include <cstdio>
#include <string>

#include "frictopt/optim/bundle_trust.hpp"
#include "frictopt/optim/luksan_vlcek.hpp"
#include "frictopt/optim/projected_subgradient.hpp"

namespace fo = frictopt::optim;

int main(int argc, char** argv) {
  // Relative accuracy of the report: |f − f*| ≤ 1e-4·max(1, |f*|).
  constexpr double kAccuracy = 1e-4;
  const std::string only = argc > 1 ? argv[1] : "";
  fo::BundleTrust::Options bt;
  bt.max_iterations = 3000;  // MXHILB and L1HILB need more than the default 500
  bt.max_evaluations = 10000;
  bt.keep_history = false;
  std::printf("| problem | set | n | f* | BT f | BT ok | evals | iters | serious | null | status | PSG f | PSG ok | PSG evals |\n");
  std::printf("|---|---|---:|---:|---:|:---:|---:|---:|---:|---:|---|---:|:---:|---:|\n");
  int solved = 0, total = 0, total_evals = 0, psg_solved = 0;
  for (const auto& set : {fo::luksan_vlcek_unconstrained(), fo::luksan_vlcek_constrained()}) {
    for (const auto& p : set) {
      if (!only.empty() && p.name != only) continue;
      fo::FunctionOracle oracle(p.evaluate);
      const fo::BundleTrust method(bt, p.constraints);
      const auto s = method.minimize(oracle, p.x0);
      fo::ProjectedSubgradient::Options po;
      po.max_evaluations = bt.max_evaluations;
      fo::FunctionOracle oracle2(p.evaluate);
      const auto b = fo::ProjectedSubgradient(po, p.constraints).minimize(oracle2, p.x0);
      const bool ok = p.solved(s.f, kAccuracy);
      const bool pok = p.solved(b.f, kAccuracy);
      solved += ok;
      psg_solved += pok;
      ++total;
      total_evals += s.evaluations;
      std::printf("| %s | %s | %ld | %.8g | %.8g | %s | %d | %d | %d | %d | %s | %.8g | %s | %d |\n",
                  p.name.c_str(), p.source.c_str(), static_cast<long>(p.dimension()), p.f_star, s.f,
                  ok ? "yes" : "**no**", s.evaluations, s.iterations, s.serious_steps, s.null_steps,
                  std::string(frictopt::to_string(s.status)).c_str(), b.f, pok ? "yes" : "no",
                  b.evaluations);
      if (!only.empty()) std::fprintf(stderr, "%s\n", s.brief_report().c_str());
    }
  }
  std::printf("\nBundle trust solved %d of %d problems with %d evaluations in total; the projected "
              "subgradient baseline solved %d of %d with %d evaluations each.\n",
              solved, total, total_evals, psg_solved, total, bt.max_evaluations);
  return solved == total ? 0 : 1;
}
