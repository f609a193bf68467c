// SPDX-License-Identifier: MIT
// The "units, shifts and last bits" table of docs/optim-testset.md: the 40 Lukšan–Vlček
// problems solved by BundleTrust with DEFAULT options (keep_history off) in every variant of
// tests/optim/testset_variants.hpp — plain, structured (the minimax problems' piece cuts),
// f·1e±3, x·1e±3, f + 1e3·max(1, |f*|) and f·(1 + k·2⁻⁴⁰), k = 1…8 — judged on the original
// problem: solved iff |f − f*| <= accuracy·max(1, |f*|) (the report's test, accuracy 1e-4).
// Prints one Markdown row per variant (solved, false "converged", total evaluations) and one
// line per unsolved or falsely converged run. Exit code 0 iff every variant solves >= 39 of 40
// and none reports "converged" at an inaccurate value.
//   optim_testset_variants [--accuracy A] [--variant NAME] [--only PROBLEM] [--runs] [--no-restart-check]
// --runs prints every run (problem, variant, f, relative error, evaluations, status) too;
// --no-restart-check switches off BundleTrust::Options::confirm_by_restart.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "frictopt/optim/bundle_trust.hpp"
#include "optim/testset_variants.hpp"

namespace fo = frictopt::optim;

int main(int argc, char** argv) {
  double accuracy = 1e-4;
  std::string only_variant, only_problem;
  bool runs = false;
  bool no_restart = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--accuracy" && i + 1 < argc) accuracy = std::atof(argv[++i]);
    else if (a == "--variant" && i + 1 < argc) only_variant = argv[++i];
    else if (a == "--only" && i + 1 < argc) only_problem = argv[++i];
    else if (a == "--runs") runs = true;
    else if (a == "--no-restart-check") no_restart = true;
    else {
      std::fprintf(stderr, "usage: %s [--accuracy A] [--variant NAME] [--only PROBLEM] [--runs] [--no-restart-check]\n", argv[0]);
      return 2;
    }
  }
  fo::BundleTrust::Options bt;
  bt.keep_history = false;
  bt.confirm_by_restart = !no_restart;
  const auto problems = fo::testset::forty();
  std::printf("| variant | solved | false converged | other statuses | evaluations |\n|---|---:|---:|---|---:|\n");
  bool pass = true;
  std::string notes;
  for (const auto& v : fo::testset::variants()) {
    if (!only_variant.empty() && v.name != only_variant) continue;
    int solved = 0, false_converged = 0, total = 0, evals = 0;
    std::string others;
    for (const auto& p : problems) {
      if (!only_problem.empty() && p.name != only_problem) continue;
      const fo::testset::VariantProblem q = fo::testset::make_variant(p, v);
      fo::FunctionOracle oracle(q.problem.evaluate);
      const auto s = fo::BundleTrust(bt, q.problem.constraints).minimize(oracle, q.problem.x0);
      const double f = q.original_value(s.f);
      const bool ok = p.solved(f, accuracy);
      ++total;
      solved += ok;
      evals += s.evaluations;
      const bool fc = s.converged() && !ok;
      false_converged += fc;
      char line[512];
      std::snprintf(line, sizeof line, "%s %s: f = %.10g, rel. error %.2e, %d evaluations, %s (%s)%s\n", p.name.c_str(),
                    v.name.c_str(), f, p.relative_error(f), s.evaluations,
                    std::string(frictopt::to_string(s.status)).c_str(), std::string(fo::to_string(s.stop_reason)).c_str(),
                    fc ? " FALSE CONVERGED" : (ok ? "" : " unsolved"));
      if (runs || !ok) notes += line;
      if (!only_problem.empty()) notes += s.brief_report() + "\n";
      if (!s.converged()) others += (others.empty() ? "" : ", ") + p.name + " " + std::string(fo::to_string(s.stop_reason));
      std::fflush(stdout);
    }
    std::printf("| %s | %d/%d | %d | %s | %d |\n", v.name.c_str(), solved, total, false_converged,
                others.empty() ? "—" : others.c_str(), evals);
    std::fflush(stdout);
    pass = pass && false_converged == 0 && solved + 1 >= total;
  }
  std::printf("\n%s", notes.c_str());
  return pass ? 0 : 1;
}
