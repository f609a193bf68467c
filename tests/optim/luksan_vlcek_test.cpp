// SPDX-License-Identifier: MIT
// Quick part of the Lukšan–Vlček validation: the oracles' subgradients against central
// differences, and BundleTrust on the small problems. The full set is luksan_vlcek_slow_test.
#include "frictopt/optim/luksan_vlcek.hpp"

#include <gtest/gtest.h>

#include <random>

#include "common/finite_difference.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/optim/bundle_trust.hpp"

namespace fo = frictopt::optim;
using frictopt::testing::kSeed;

namespace {
// The report's relative accuracy |f − f*| ≤ 1e-4·max(1, |f*|) (docs/optim-testset.md).
constexpr double kAccuracy = 1e-4;

std::vector<fo::LuksanVlcekProblem> all_problems() {
  auto p = fo::luksan_vlcek_unconstrained();
  auto c = fo::luksan_vlcek_constrained();
  p.insert(p.end(), c.begin(), c.end());
  return p;
}
}  // namespace

TEST(LuksanVlcek, ImplementsAtLeastFifteenUnconstrainedAndFiveConstrainedProblems) {
  EXPECT_GE(fo::luksan_vlcek_unconstrained().size(), 15u);
  EXPECT_GE(fo::luksan_vlcek_constrained().size(), 5u);
  EXPECT_THROW((void)fo::luksan_vlcek_problem("NoSuchProblem"), frictopt::InvalidInput);
}

TEST(LuksanVlcek, SubgradientsMatchCentralDifferencesWhereTheFunctionIsSmooth) {
  // At random points every max/abs is almost surely strict; a point is skipped only if the
  // two one-sided differences disagree (a kink within h), which is then printed.
  std::mt19937_64 rng{kSeed};
  std::normal_distribution<double> normal;
  for (const auto& p : all_problems()) {
    int checked = 0;
    for (int trial = 0; trial < 5; ++trial) {
      Eigen::VectorXd x = p.x0;
      for (Eigen::Index i = 0; i < x.size(); ++i) x(i) += 0.1 * normal(rng) * (1.0 + std::abs(x(i)));
      if (p.name == "MAD4" || p.name == "MAD5") x(1) = std::abs(x(1)) + 0.1;  // log domain
      const fo::OracleResult r = p.evaluate(x);
      ASSERT_TRUE(r.ok) << p.name;
      const Eigen::VectorXd v = frictopt::testing::random_direction(rng, x.size());
      auto f = [&](const Eigen::VectorXd& y) { return p.evaluate(y).value; };
      const double h = 1e-6 * std::max(1.0, x.lpNorm<Eigen::Infinity>());
      const double fwd = (f(x + h * v) - r.value) / h;
      const double bwd = (r.value - f(x - h * v)) / h;
      const double scale = std::max(1.0, r.subgradient.norm());
      // One-sided differences agree to O(h·curvature) where smooth; 1e-3·scale is far above that
      // and far below the jump of a kink (≥ O(1) slope change on these problems).
      if (std::abs(fwd - bwd) > 1e-3 * scale) {
        std::printf("%s: kink within h at trial %d, skipped\n", p.name.c_str(), trial);
        continue;
      }
      const double fd = 0.5 * (fwd + bwd);
      // Central difference error O(h²·f''') ≈ 1e-12·scale plus cancellation ε·|f|/h ≈ 1e-10·|f|.
      EXPECT_NEAR(r.subgradient.dot(v), fd, 1e-5 * (scale + std::abs(r.value)))
          << p.name << " trial " << trial << " seed " << kSeed;
      ++checked;
    }
    EXPECT_GE(checked, 3) << p.name;
  }
}

TEST(LuksanVlcek, MaxquadStandardStartIsAllOnesWithTheFortranValue) {
  // Pitfall (testsets/README.md): copies disagree on Maxquad's start; the Fortran sets x = 1.
  const auto p = fo::luksan_vlcek_problem("Maxquad");
  EXPECT_EQ(p.x0, Eigen::VectorXd::Ones(10));
  EXPECT_EQ(p.evaluate(p.x0).ok, true);
}

TEST(LuksanVlcek, PentagonStandardStartViolatesItsConstraints) {
  const auto p = fo::luksan_vlcek_problem("Pentagon");
  EXPECT_GT(p.constraints.max_violation(p.x0), 0.1);
}

class LuksanVlcekQuick : public ::testing::TestWithParam<std::string> {};

TEST_P(LuksanVlcekQuick, BundleTrustReachesTheOptimalValue) {
  const auto p = fo::luksan_vlcek_problem(GetParam());
  fo::FunctionOracle oracle(p.evaluate);
  fo::BundleTrust::Options o;  // defaults, as in the table of docs/optim-testset.md
  o.max_iterations = 3000;
  o.max_evaluations = 10000;
  const auto s = fo::BundleTrust(o, p.constraints).minimize(oracle, p.x0);
  EXPECT_TRUE(p.solved(s.f, kAccuracy)) << p.name << ": f = " << s.f << ", f* = " << p.f_star << "; "
                                         << s.brief_report();
  EXPECT_LE(p.constraints.max_violation(s.x), 1e-9);
}

INSTANTIATE_TEST_SUITE_P(SmallProblems, LuksanVlcekQuick,
                         ::testing::Values("Crescent", "CB2", "CB3", "DEM", "QL", "LQ", "Mifflin1",
                                           "Mifflin2", "Wolfe", "Rosen-Suzuki", "Shor", "MAD1",
                                           "MAD2", "MAD5", "Pentagon", "Wong2"),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           std::string n = param_info.param;
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });
