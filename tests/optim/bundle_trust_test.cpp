// SPDX-License-Identifier: MIT
#include "frictopt/optim/bundle_trust.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "frictopt/core/error.hpp"

namespace fo = frictopt::optim;
using frictopt::Status;

namespace {

// The stopping test bounds ‖z + ω‖ and the aggregate error by ε; on these piecewise-linear
// and quadratic problems with O(1) slopes that puts f within a small multiple of ε of f*.
constexpr double kEpsilon = 1e-6;
constexpr double kFTol = 1e-5;
// Iterates are QP solutions; constraint violations are round-off of the direction QP.
constexpr double kFeasTol = 1e-9;

// f(x) = Σ_i w_i |x_i − c_i| (convex, kinks at the minimizer).
fo::FunctionOracle weighted_l1(Eigen::VectorXd w, Eigen::VectorXd c) {
  return fo::FunctionOracle([w, c](const Eigen::Ref<const Eigen::VectorXd>& x) {
    const Eigen::VectorXd r = x - c;
    Eigen::VectorXd g(r.size());
    for (Eigen::Index i = 0; i < r.size(); ++i) g(i) = w(i) * (r(i) >= 0 ? 1.0 : -1.0);
    return fo::OracleResult::success(w.dot(r.cwiseAbs()), g);
  });
}

// f(x) = max_i x_i.
fo::FunctionOracle max_oracle() {
  return fo::FunctionOracle([](const Eigen::Ref<const Eigen::VectorXd>& x) {
    Eigen::Index k = 0;
    const double f = x.maxCoeff(&k);
    return fo::OracleResult::success(f, Eigen::VectorXd::Unit(x.size(), k));
  });
}

fo::BundleTrust::Options tight() {
  fo::BundleTrust::Options o;
  o.epsilon = kEpsilon;
  return o;
}

}  // namespace

TEST(BundleTrust, MinimizesAConvexPiecewiseLinearFunctionToAlmostStationarity) {
  auto oracle = weighted_l1(Eigen::Vector3d(1.0, 2.0, 0.5), Eigen::Vector3d(1.0, -2.0, 3.0));
  const auto s = fo::BundleTrust(tight()).minimize(oracle, Eigen::Vector3d(5.0, 5.0, 5.0));
  ASSERT_EQ(s.status, Status::kConverged) << s.brief_report();
  EXPECT_NEAR(s.f, 0.0, kFTol);
  EXPECT_LE(s.stationarity, kEpsilon);
  EXPECT_LE(s.aggregate_error, kEpsilon);
  EXPECT_EQ(s.iterations, s.serious_steps + s.null_steps);
  EXPECT_EQ(static_cast<int>(s.history.size()), s.iterations);
}

TEST(BundleTrust, ConvergesWithTheThesisVariantThatNeverEnlargesT) {
  auto o = tight();
  o.enlarge_t = false;
  auto oracle = weighted_l1(Eigen::Vector2d(1.0, 3.0), Eigen::Vector2d(-1.0, 2.0));
  const auto s = fo::BundleTrust(o).minimize(oracle, Eigen::Vector2d(3.0, -3.0));
  ASSERT_EQ(s.status, Status::kConverged) << s.brief_report();
  EXPECT_NEAR(s.f, 0.0, kFTol);
}

TEST(BundleTrust, KeepsEveryIterateFeasibleUnderInequalitiesAndBounds) {
  // min |x1 − 2| + |x2 − 2| s.t. x1 + x2 ≤ 1, x ≥ 0: f* = 3 on the whole edge x1 + x2 = 1.
  fo::LinearConstraints k;
  k.lower = Eigen::Vector2d(0.0, 0.0);
  k.A_in = Eigen::MatrixXd{{1.0, 1.0}};
  k.b_in = Eigen::VectorXd::Ones(1);
  auto o = tight();
  double worst = 0.0;
  o.on_iteration = [&](const fo::BundleTrust::IterationSummary& it) {
    worst = std::max(worst, k.max_violation(it.x));
    for (const auto& b : it.bundle)
      if (!b.is_aggregate()) worst = std::max(worst, k.max_violation(b.y));
    return frictopt::CallbackResult::kContinue;
  };
  auto oracle = weighted_l1(Eigen::Vector2d(1.0, 1.0), Eigen::Vector2d(2.0, 2.0));
  const auto s = fo::BundleTrust(o, k).minimize(oracle, Eigen::Vector2d(0.0, 0.0));
  ASSERT_EQ(s.status, Status::kConverged) << s.brief_report();
  EXPECT_NEAR(s.f, 3.0, kFTol);
  EXPECT_LE(worst, kFeasTol);
  EXPECT_FALSE(s.start_projected);
}

TEST(BundleTrust, KeepsEqualityConstraintsExactlyAlongTheRun) {
  // min max_i x_i s.t. Σx = 3: f* = 1 at (1,1,1).
  fo::LinearConstraints k;
  k.A_eq = Eigen::MatrixXd::Ones(1, 3);
  k.b_eq = Eigen::VectorXd::Constant(1, 3.0);
  auto o = tight();
  double worst = 0.0;
  o.on_iteration = [&](const fo::BundleTrust::IterationSummary& it) {
    worst = std::max(worst, k.max_violation(it.x));
    return frictopt::CallbackResult::kContinue;
  };
  auto oracle = max_oracle();
  const auto s = fo::BundleTrust(o, k).minimize(oracle, Eigen::Vector3d(3.0, 0.0, 0.0));
  ASSERT_EQ(s.status, Status::kConverged) << s.brief_report();
  EXPECT_NEAR(s.f, 1.0, kFTol);
  EXPECT_LE(worst, kFeasTol);
}

TEST(BundleTrust, ProjectsAnInfeasibleStartAndReportsIt) {
  fo::LinearConstraints k;
  k.upper = Eigen::Vector2d(-1.0, 10.0);  // x1 ≤ −1: minimizer of |x1| + |x2| is (−1, 0)
  auto oracle = weighted_l1(Eigen::Vector2d(1.0, 1.0), Eigen::Vector2d(0.0, 0.0));
  const auto s = fo::BundleTrust(tight(), k).minimize(oracle, Eigen::Vector2d(2.0, 1.0));
  ASSERT_EQ(s.status, Status::kConverged) << s.brief_report();
  EXPECT_TRUE(s.start_projected);
  EXPECT_NEAR(s.projection_distance, 3.0, 1e-12);  // (2,1) → (−1,1); one QP solve, round-off
  EXPECT_NEAR(s.f, 1.0, kFTol);
}

TEST(BundleTrust, RejectsAnEmptyFeasibleSetWithAClearError) {
  fo::LinearConstraints k;
  k.A_in = Eigen::MatrixXd{{1.0, 0.0}, {-1.0, 0.0}};
  k.b_in = Eigen::Vector2d(-1.0, -1.0);  // x1 ≤ −1 and x1 ≥ 1
  auto oracle = max_oracle();
  try {
    (void)fo::BundleTrust(tight(), k).minimize(oracle, Eigen::Vector2d(0.0, 0.0));
    FAIL() << "expected InvalidInput";
  } catch (const frictopt::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("feasible set is empty"), std::string::npos) << e.what();
  }
}

TEST(BundleTrust, RejectsInconsistentDimensions) {
  fo::LinearConstraints k;
  k.lower = Eigen::VectorXd::Zero(3);
  auto oracle = max_oracle();
  EXPECT_THROW((void)fo::BundleTrust(tight(), k).minimize(oracle, Eigen::Vector2d(1.0, 1.0)),
               frictopt::InvalidInput);
  fo::FunctionOracle wrong([](const Eigen::Ref<const Eigen::VectorXd>&) {
    return fo::OracleResult::success(0.0, Eigen::VectorXd::Zero(5));
  });
  EXPECT_THROW((void)fo::BundleTrust(tight()).minimize(wrong, Eigen::Vector2d(1.0, 1.0)),
               frictopt::InvalidInput);
}

TEST(BundleTrust, OptionsValidationNamesFieldValueAndExpectation) {
  auto o = tight();
  o.m2 = 0.05;  // < m1 = 0.1
  try {
    fo::BundleTrust bt(o);
    FAIL() << "expected InvalidInput";
  } catch (const frictopt::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("BundleTrust::Options: m2 = 0.05; expected in (m1, 1)"),
              std::string::npos)
        << e.what();
  }
  o = tight();
  o.max_bundle_size = 2;
  EXPECT_THROW(fo::BundleTrust{o}, frictopt::InvalidInput);
}

TEST(BundleTrust, ShrinksTheStepWhereTheOracleCannotEvaluate) {
  // f = ‖x − (1,1)‖₁ but the oracle fails outside the ball ‖x‖ ≤ 2 (think: contact solve fails).
  int failures = 0;
  fo::FunctionOracle oracle([&](const Eigen::Ref<const Eigen::VectorXd>& x) {
    if (x.norm() > 2.0) {
      ++failures;
      return fo::OracleResult::failure("outside the solver's domain");
    }
    const Eigen::Vector2d r = x - Eigen::Vector2d(1.0, 1.0);
    return fo::OracleResult::success(r.cwiseAbs().sum(),
                                     Eigen::Vector2d(r(0) >= 0 ? 1 : -1, r(1) >= 0 ? 1 : -1));
  });
  auto o = tight();
  o.t_max = 100.0;  // first trial step of length ~140: far outside the domain
  const auto s = fo::BundleTrust(o).minimize(oracle, Eigen::Vector2d(-1.0, -1.0));
  ASSERT_EQ(s.status, Status::kConverged) << s.brief_report();
  EXPECT_NEAR(s.f, 0.0, kFTol);
  EXPECT_GT(s.failed_evaluations, 0);
  EXPECT_EQ(s.failed_evaluations, failures);
}

TEST(BundleTrust, TreatsNonFiniteOracleOutputAsAFailedEvaluation) {
  fo::FunctionOracle nan_at_start([](const Eigen::Ref<const Eigen::VectorXd>& x) {
    return fo::OracleResult::success(std::numeric_limits<double>::quiet_NaN(), Eigen::VectorXd::Zero(x.size()));
  });
  const auto s0 = fo::BundleTrust(tight()).minimize(nan_at_start, Eigen::Vector2d(1.0, 1.0));
  EXPECT_EQ(s0.status, Status::kNumericalFailure) << s0.brief_report();

  // Finite at the start, infinite everywhere else: the inner iteration must give up (limits).
  const Eigen::Vector2d x0(1.0, 1.0);
  fo::FunctionOracle inf_elsewhere([x0](const Eigen::Ref<const Eigen::VectorXd>& x) {
    const double f = (x - x0).norm() == 0.0 ? 1.0 : std::numeric_limits<double>::infinity();
    return fo::OracleResult::success(f, Eigen::Vector2d(1.0, 0.0));
  });
  const auto s = fo::BundleTrust(tight()).minimize(inf_elsewhere, x0);
  EXPECT_EQ(s.status, Status::kStalled) << s.brief_report();
  EXPECT_EQ(s.failed_evaluations, s.evaluations - 1);
  EXPECT_LE(s.evaluations, 1 + tight().max_inner_iterations);
  EXPECT_EQ(s.f, 1.0);
}

TEST(BundleTrust, StopsAtTheEvaluationAndIterationLimits) {
  auto o = tight();
  o.epsilon = 0.0;  // never "almost stationary": only limits can end the run
  o.max_evaluations = 7;
  auto oracle = weighted_l1(Eigen::Vector2d(1.0, 1.0), Eigen::Vector2d(0.3, 0.7));
  const auto s = fo::BundleTrust(o).minimize(oracle, Eigen::Vector2d(5.0, 5.0));
  EXPECT_EQ(s.status, Status::kMaxIterations);
  EXPECT_TRUE(s.evaluation_limit) << s.message;
  EXPECT_LE(s.evaluations, 7);
  o.max_evaluations = 100000;
  o.max_iterations = 4;
  const auto s2 = fo::BundleTrust(o).minimize(oracle, Eigen::Vector2d(5.0, 5.0));
  EXPECT_EQ(s2.status, Status::kMaxIterations);
  EXPECT_FALSE(s2.evaluation_limit) << s2.message;
  EXPECT_EQ(s2.iterations, 4);
}

TEST(BundleTrust, CallbackCanStopTheRunAndTheRunResumesFromItsState) {
  auto oracle = weighted_l1(Eigen::Vector3d(1.0, 2.0, 0.5), Eigen::Vector3d(1.0, -2.0, 3.0));
  const Eigen::Vector3d x0(5.0, 5.0, 5.0);
  const auto full = fo::BundleTrust(tight()).minimize(oracle, x0);
  ASSERT_EQ(full.status, Status::kConverged);
  ASSERT_GT(full.iterations, 5);

  auto o = tight();
  o.on_iteration = [](const fo::BundleTrust::IterationSummary& it) {
    return it.iteration >= 5 ? frictopt::CallbackResult::kStop : frictopt::CallbackResult::kContinue;
  };
  const auto first = fo::BundleTrust(o).minimize(oracle, x0);
  EXPECT_EQ(first.status, Status::kStoppedByCallback);
  EXPECT_EQ(first.iterations, 5);

  // Same state, same arithmetic: the resumed run ends exactly where the uninterrupted one did.
  const auto rest = fo::BundleTrust(tight()).resume(oracle, first.last_state);
  ASSERT_EQ(rest.status, Status::kConverged) << rest.brief_report();
  EXPECT_EQ(rest.iterations, full.iterations);
  EXPECT_EQ(rest.evaluations, full.evaluations);
  EXPECT_EQ(rest.f, full.f);
  EXPECT_EQ(rest.x, full.x);
}

TEST(BundleTrust, BriefReportNamesStatusAndCounters) {
  auto oracle = max_oracle();
  fo::LinearConstraints k;
  k.lower = Eigen::Vector2d(0.0, 0.0);
  const auto s = fo::BundleTrust(tight(), k).minimize(oracle, Eigen::Vector2d(1.0, 2.0));
  const std::string r = s.brief_report();
  EXPECT_NE(r.find("converged"), std::string::npos) << r;
  EXPECT_NE(r.find("evaluations"), std::string::npos) << r;
  EXPECT_NEAR(s.f, 0.0, kFTol);
}

// ---- scale invariance, adaptive step bound, no false "converged" (docs/optim.md) ----------

namespace {
// CB2-like max of three smooth pieces (Charalambous–Bandler), scaled in f by cf and in x by cx:
// f̃(x̃) = cf·f(x̃/cx). Minimum cf·1.9522245 (Lukšan–Vlček TEST19 #3).
fo::FunctionOracle scaled_cb2(double cf, double cx) {
  return fo::FunctionOracle([cf, cx](const Eigen::Ref<const Eigen::VectorXd>& xs) {
    const Eigen::Vector2d x = xs / cx;
    const double f1 = x(0) * x(0) + std::pow(x(1), 4);
    const double f2 = std::pow(2 - x(0), 2) + std::pow(2 - x(1), 2);
    const double f3 = 2 * std::exp(x(1) - x(0));
    Eigen::Vector2d g;
    double f = f1;
    g << 2 * x(0), 4 * std::pow(x(1), 3);
    if (f2 > f) {
      f = f2;
      g << -2 * (2 - x(0)), -2 * (2 - x(1));
    }
    if (f3 > f) {
      f = f3;
      g << -f3, f3;
    }
    return fo::OracleResult::success(cf * f, (cf / cx) * g);
  });
}
constexpr double kCb2Min = 1.9522245;
}  // namespace

// Same decisions up to round-off: identical step kinds along the common history while the
// center is above the final value by more than 1e-8 relative, and the stop at most a few
// iterations apart. At the minimizer itself — the restart check (Options::confirm_by_restart)
// re-explores it — a trial's Δ = f(y) − f(x_k) is round-off of f, and serious or null is a coin
// flip of the last bits; the power-of-two units of invariance_test.cpp check those decisions
// bit for bit.
static void expect_same_run(const fo::BundleTrust::Summary& a, const fo::BundleTrust::Summary& b, const std::string& what) {
  const std::size_t common = std::min(a.history.size(), b.history.size());
  const double final_b = b.f, tolerance = 1e-8 * std::abs(b.f);
  for (std::size_t i = 0; i < common; ++i)
    if (b.history[i].f > final_b + tolerance) {
      EXPECT_EQ(a.history[i].step, b.history[i].step) << what << ", iteration " << i + 1;
    }
  EXPECT_LE(std::abs(a.iterations - b.iterations), 3) << what;
  EXPECT_LE(std::abs(a.evaluations - b.evaluations), 3) << what;
}

TEST(BundleTrust, ScalingTheObjectiveChangesNoDecision) {
  // The step rule, the locality measure and the stopping test are homogeneous in f: f·c takes
  // the same steps for c from 1e-6 to 1e6.
  auto ref_oracle = scaled_cb2(1.0, 1.0);
  const auto ref = fo::BundleTrust({}).minimize(ref_oracle, Eigen::Vector2d(1.0, -0.1));
  ASSERT_TRUE(ref.converged()) << ref.brief_report();
  EXPECT_NEAR(ref.f, kCb2Min, 1e-4 * kCb2Min);
  for (const double c : {1e-6, 1e6}) {
    auto oracle = scaled_cb2(c, 1.0);
    const auto s = fo::BundleTrust({}).minimize(oracle, Eigen::Vector2d(1.0, -0.1));
    ASSERT_TRUE(s.converged()) << "f·" << c << ": " << s.brief_report();
    expect_same_run(s, ref, "f·" + std::to_string(c));
    EXPECT_NEAR(s.f / c, ref.f, 1e-7 * kCb2Min) << "f·" << c;  // both within the tolerance of f*
  }
}

TEST(BundleTrust, ScaleObjectiveOptionGivesTheSameRun) {
  // Regression: scale_objective = true used to stop after one iteration at twice
  // the optimum, because the absolute test met a rescaled f. Now the option changes nothing.
  auto oracle = scaled_cb2(1e3, 1.0);
  fo::BundleTrust::Options o;
  const auto plain = fo::BundleTrust(o).minimize(oracle, Eigen::Vector2d(1.0, -0.1));
  o.scale_objective = true;
  const auto scaled = fo::BundleTrust(o).minimize(oracle, Eigen::Vector2d(1.0, -0.1));
  ASSERT_TRUE(scaled.converged()) << scaled.brief_report();
  expect_same_run(scaled, plain, "scale_objective");
  EXPECT_NEAR(scaled.f, 1e3 * kCb2Min, 1e-4 * 1e3 * kCb2Min);
}

TEST(BundleTrust, StepBoundAdaptsToVariablesScaledByAThousand) {
  // With the first step fixed from the first subgradient and never revisited, x·1e3 crept with
  // thousands of tiny steps. The bound now grows with the observed model quality.
  for (const double cx : {1e-3, 1e3}) {
    auto oracle = scaled_cb2(1.0, cx);
    const auto s = fo::BundleTrust({}).minimize(oracle, cx * Eigen::Vector2d(1.0, -0.1));
    ASSERT_TRUE(s.converged()) << "x·" << cx << ": " << s.brief_report();
    EXPECT_NEAR(s.f, kCb2Min, 1e-4 * kCb2Min) << "x·" << cx;
    EXPECT_LE(s.evaluations, 100) << "x·" << cx << ": " << s.brief_report();
  }
}

TEST(BundleTrust, LargeSubgradientsNeitherStallTheQpNorCreep) {
  // ‖g‖ ~ 1e7: the unscaled direction QP reported "unbounded" at the first iteration (before
  // the QP was scaled, docs/optim.md "The step bound"). Weighted ℓ1 with weights 1e6..4e6: minimum 0 at c.
  auto oracle = weighted_l1(Eigen::Vector3d(1e6, 4e6, 2e6), Eigen::Vector3d(1.0, -2.0, 3.0));
  const auto s = fo::BundleTrust({}).minimize(oracle, Eigen::Vector3d(50.0, 50.0, 50.0));
  ASSERT_TRUE(s.converged()) << s.brief_report();
  EXPECT_LE(s.f, 1e-4 * 1e6);  // relative to the weights: the same accuracy as with weights O(1)
  EXPECT_LE(s.evaluations, 200) << s.brief_report();
}

TEST(BundleTrust, ConvergedRunsPassTheStationarityCertificate) {
  // "converged" is only reported with a certificate distance <= ε·G (docs/optim.md).
  auto oracle = weighted_l1(Eigen::Vector3d(1.0, 2.0, 0.5), Eigen::Vector3d(1.0, -2.0, 3.0));
  const auto s = fo::BundleTrust(tight()).minimize(oracle, Eigen::Vector3d(5.0, 5.0, 5.0));
  ASSERT_TRUE(s.converged());
  EXPECT_EQ(s.stop_reason, fo::StopReason::kCertifiedStationary);
  ASSERT_TRUE(std::isfinite(s.certificate_distance));
  EXPECT_LE(s.certificate_distance, kEpsilon * s.subgradient_scale);
  EXPECT_EQ(fo::to_string(s.stop_reason), "certified_stationary");
}

TEST(BundleTrust, NamesWhichLimitStoppedTheRun) {
  auto o = tight();
  o.epsilon = 0.0;
  o.max_iterations = 3;
  auto oracle = weighted_l1(Eigen::Vector2d(1.0, 1.0), Eigen::Vector2d(0.3, 0.7));
  const auto s = fo::BundleTrust(o).minimize(oracle, Eigen::Vector2d(5.0, 5.0));
  EXPECT_EQ(s.stop_reason, fo::StopReason::kIterationLimit);
  EXPECT_EQ(fo::to_string(s.stop_reason), "max_iterations");
}
