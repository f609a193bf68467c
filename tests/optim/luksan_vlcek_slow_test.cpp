// SPDX-License-Identifier: MIT
// The whole Lukšan–Vlček table of docs/optim-testset.md (40 problems + 32 scaled variants) with
// DEFAULT options, and the tight run (ε = 1e-7 for accuracy 1e-6). Problems listed as open do
// not reach f* yet (docs/optim-testset.md says why); they are checked not to be reported solved
// by accident, so that fixing one fails this test until the list is updated.
#include <gtest/gtest.h>

#include <cstdio>
#include <set>
#include <string>

#include "frictopt/optim/bundle_trust.hpp"
#include "optim/testset_variants.hpp"
#include "testset/luksan_vlcek.hpp"

namespace fo = frictopt::optim;

namespace {

std::vector<fo::LuksanVlcekProblem> table() {
  auto p = fo::luksan_vlcek_unconstrained();
  for (auto set : {fo::luksan_vlcek_constrained(), fo::luksan_vlcek_scaled_variants()})
    p.insert(p.end(), set.begin(), set.end());
  return p;
}

void check_table(const fo::BundleTrust::Options& options, double accuracy, const std::set<std::string>& open) {
  int solved = 0;
  for (const auto& p : table()) {
    fo::FunctionOracle oracle(p.evaluate);
    const auto s = fo::BundleTrust(options, p.constraints).minimize(oracle, p.x0);
    const bool ok = p.solved(s.f, accuracy);
    solved += ok;
    EXPECT_LE(p.constraints.max_violation(s.x), 1e-9) << p.name;
    // A run that says "converged" must be accurate, open problem or not.
    if (s.converged()) {
      EXPECT_TRUE(ok) << p.name << " reports converged at an inaccurate value; " << s.brief_report();
    }
    if (open.count(p.name)) {
      EXPECT_FALSE(ok) << p.name << " is solved now: remove it from the open list";
      continue;
    }
    EXPECT_TRUE(ok) << p.name << ": f = " << s.f << ", f* = " << p.f_star << ", relative error "
                    << p.relative_error(s.f) << "; " << s.brief_report();
  }
  std::printf("accuracy %g, epsilon %g: %d of %zu solved\n", accuracy, options.epsilon, solved, table().size());
}

}  // namespace

TEST(LuksanVlcekFullSet, DefaultOptionsSolveTheTableExceptTheOpenProblems) {
  fo::BundleTrust::Options o;
  o.keep_history = false;
  // The report's relative accuracy |f − f*| <= 1e-4·max(unit, |f*|).
  check_table(o, 1e-4, {"BPfilter"});
}

TEST(LuksanVlcekFullSet, EpsilonOneTenthOfTheAccuracyReachesOneInAMillion) {
  fo::BundleTrust::Options o;
  o.keep_history = false;
  o.epsilon = 1e-7;
  check_table(o, 1e-6, {"BPfilter"});
}

// The tight target: ε = 1e-6 for accuracy 1e-6 with otherwise default options. HS114
// said "converged" 4.8e-6 off f* here until the default confirmation in the point's units
// (docs/optim-testset.md).
TEST(LuksanVlcekFullSet, EpsilonOneInAMillionReachesOneInAMillion) {
  fo::BundleTrust::Options o;
  o.keep_history = false;
  o.epsilon = 1e-6;
  check_table(o, 1e-6, {"BPfilter"});
}

// Regression (in the slow program: 40 s alone, 335 s under the sanitizers, whose quick optim
// tests run the same code): TR48 starts at x_1 = 0, so the automatic first step is
// 10 while ‖x*‖∞ = 1086; with the locality unit fixed at t_1 every cut beyond a few units was
// "far", t was bisected to 0.005 and the run crept (2.2e-2 off f* after 3000 iterations). The
// unit now grows with the distance the centers have travelled (docs/optim.md).
TEST(LuksanVlcekRegression, Tr48IsSolvedWithDefaultOptions) {
  const auto p = fo::luksan_vlcek_problem("TR48");
  fo::BundleTrust::Options o;
  o.keep_history = false;
  fo::FunctionOracle oracle(p.evaluate);
  const auto s = fo::BundleTrust(o, p.constraints).minimize(oracle, p.x0);
  EXPECT_TRUE(p.solved(s.f, 1e-4)) << s.brief_report();
  EXPECT_TRUE(s.converged()) << s.brief_report();
}

// The "units, shifts and last bits" table of docs/optim-testset.md: the 40 problems in every
// variant of tests/optim/testset_variants.hpp (plain, structured, f·1e±3, x·1e±3,
// f + 1e3·max(1, |f*|), f·(1 + k·2⁻⁴⁰) for k = 1…8) with default options, judged on the original
// problem at the report's accuracy 1e-4. Every variant: at least 39 of 40 solved (BPfilter may
// end with an honest status) and no "converged" at an inaccurate value. Before the invariant
// tests and the restart check: 3 false "converged" in the scaled variants, 6 in the perturbed
// ones, 6 in the shifted one.
TEST(LuksanVlcekFullSet, EveryVariantOfUnitsShiftAndLastBitsIsSolvedWithoutAFalseConverged) {
  fo::BundleTrust::Options o;
  o.keep_history = false;
  const auto problems = fo::testset::forty();
  for (const auto& v : fo::testset::variants()) {
    int solved = 0, evaluations = 0;
    for (const auto& p : problems) {
      const fo::testset::VariantProblem q = fo::testset::make_variant(p, v);
      fo::FunctionOracle oracle(q.problem.evaluate);
      const auto s = fo::BundleTrust(o, q.problem.constraints).minimize(oracle, q.problem.x0);
      const double f = q.original_value(s.f);
      const bool ok = p.solved(f, 1e-4);
      solved += ok;
      evaluations += s.evaluations;
      if (s.converged()) {
        EXPECT_TRUE(ok) << p.name << " " << v.name << " reports converged " << p.relative_error(f)
                        << " off f*; " << s.brief_report();
      }
      if (p.name != "BPfilter") {
        EXPECT_TRUE(ok) << p.name << " " << v.name << ": relative error " << p.relative_error(f) << "; "
                        << s.brief_report();
      }
    }
    EXPECT_GE(solved, 39) << v.name;
    std::printf("%s: %d of %zu solved, %d evaluations\n", v.name.c_str(), solved, problems.size(), evaluations);
  }
}
