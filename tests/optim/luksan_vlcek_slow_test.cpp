// SPDX-License-Identifier: MIT
// The whole implemented Lukšan–Vlček set with the options of docs/optim-testset.md.
#include <gtest/gtest.h>

#include "frictopt/optim/bundle_trust.hpp"
#include "frictopt/optim/luksan_vlcek.hpp"

namespace fo = frictopt::optim;

namespace {
// The report's relative accuracy |f − f*| ≤ 1e-4·max(1, |f*|).
constexpr double kAccuracy = 1e-4;
}  // namespace

TEST(LuksanVlcekFullSet, BundleTrustSolvesEveryImplementedProblem) {
  for (const auto& set : {fo::luksan_vlcek_unconstrained(), fo::luksan_vlcek_constrained()}) {
    for (const auto& p : set) {
      fo::FunctionOracle oracle(p.evaluate);
      fo::BundleTrust::Options o;
      o.max_iterations = 3000;
      o.max_evaluations = 10000;
      o.keep_history = false;
      const auto s = fo::BundleTrust(o, p.constraints).minimize(oracle, p.x0);
      EXPECT_TRUE(p.solved(s.f, kAccuracy)) << p.name << ": f = " << s.f << ", f* = " << p.f_star
                                             << "; " << s.brief_report();
      EXPECT_LE(p.constraints.max_violation(s.x), 1e-9) << p.name;
    }
  }
}
