// SPDX-License-Identifier: MIT
// The four 1D examples of the thesis' §2.4 (docs/theory/stationarity.md §1) and constrained
// examples.
#include "frictopt/optim/stationarity.hpp"

#include <gtest/gtest.h>

#include "frictopt/core/error.hpp"

namespace fo = frictopt::optim;

namespace {
// δ comes from one small QP on O(1) data; round-off level with a wide margin.
constexpr double kTol = 1e-10;

Eigen::MatrixXd pieces(std::initializer_list<double> slopes) {
  Eigen::MatrixXd m(1, static_cast<Eigen::Index>(slopes.size()));
  Eigen::Index j = 0;
  for (double s : slopes) m(0, j++) = s;
  return m;
}

double distance(const Eigen::MatrixXd& xi, double x, const fo::LinearConstraints& k = {}) {
  const auto c = fo::stationarity_certificate(xi, Eigen::VectorXd::Constant(1, x), k);
  EXPECT_EQ(c.status, frictopt::Status::kConverged) << c.brief_report();
  return c.distance;
}
}  // namespace

TEST(DistinctColumns, GroupsRelativeToTheLargestEntryInAnyUnits) {
  // Columns 0 and 2 agree to 1e-14 relative, column 1 differs at O(1): two groups, whether the
  // entries are O(1) or O(1e-20) (a floor of 1 in the scale would merge all three at 1e-20).
  Eigen::MatrixXd Xi(2, 3);
  Xi << 1.0, 0.5, 1.0 + 1e-14, -2.0, 3.0, -2.0;
  for (const double units : {1.0, 1e-20, 1e20}) {
    std::vector<Eigen::Index> group;
    const std::vector<Eigen::Index> rep = fo::distinct_columns(units * Xi, 1e-12, group);
    EXPECT_EQ(rep, (std::vector<Eigen::Index>{0, 1})) << "units " << units;
    EXPECT_EQ(group, (std::vector<Eigen::Index>{0, 1, 0})) << "units " << units;
  }
}

TEST(StationarityCertificate, Example241IsPseudostationaryButNotClarkeStationary) {
  // f(x) = x built from selections {x, −x}: only x is essentially active at 0.
  EXPECT_NEAR(distance(pieces({1.0}), 0.0), 1.0, kTol);        // Clarke: ∂f(0) = {1}
  EXPECT_NEAR(distance(pieces({1.0, -1.0}), 0.0), 0.0, kTol);  // pseudo: Γ_f(0) = [−1, 1]
}

TEST(StationarityCertificate, Example242LocalMaximumIsClarkeStationary) {
  // f = −|x|: ∂f(0) = conv{−1, 1} ∋ 0 (while ∂_M f(0) = {−1, 1} is not convex).
  EXPECT_NEAR(distance(pieces({-1.0, 1.0}), 0.0), 0.0, kTol);
}

TEST(StationarityCertificate, Example243IsClarkeStationaryWithZeroOnTheHull) {
  // f = −x for x ≥ 0, 0 for x < 0: ∂f(0) = [−1, 0].
  const auto c = fo::stationarity_certificate(pieces({-1.0, 0.0}), Eigen::VectorXd::Zero(1));
  EXPECT_NEAR(c.distance, 0.0, kTol);
  EXPECT_NEAR(c.weights(1), 1.0, kTol);  // attained by the selection 0
}

TEST(StationarityCertificate, Example244AbsoluteValueIsStationaryWithEqualWeights) {
  const auto c = fo::stationarity_certificate(pieces({1.0, -1.0}), Eigen::VectorXd::Zero(1));
  EXPECT_NEAR(c.distance, 0.0, kTol);
  EXPECT_NEAR(c.weights(0), 0.5, kTol);
  EXPECT_NEAR(c.weights(1), 0.5, kTol);
  EXPECT_NEAR(c.weights.sum(), 1.0, kTol);
}

TEST(StationarityCertificate, LinearFunctionOnAnIntervalIsStationaryOnlyAtTheLeftEnd) {
  // f(x) = x on [0, 1]: δ = 0 at 0 (normal cone (−∞, 0]), 1 at 0.5 and at 1.
  fo::LinearConstraints k;
  k.lower = Eigen::VectorXd::Zero(1);
  k.upper = Eigen::VectorXd::Ones(1);
  const auto c0 = fo::stationarity_certificate(pieces({1.0}), Eigen::VectorXd::Zero(1), k);
  EXPECT_NEAR(c0.distance, 0.0, kTol);
  EXPECT_NEAR(c0.normal_part(0), -1.0, kTol);
  ASSERT_EQ(c0.active_names.size(), 1u);
  EXPECT_EQ(c0.active_names[0], "lower[0]");
  EXPECT_NEAR(distance(pieces({1.0}), 0.5, k), 1.0, kTol);
  EXPECT_NEAR(distance(pieces({1.0}), 1.0, k), 1.0, kTol);
}

TEST(StationarityCertificate, TwoDimensionalKinkOnAHalfPlaneIsStationary) {
  // f = |x1| + x2 on {x2 ≥ 0} at 0: ∂f = [−1,1]×{1}, N = {(0, −η)}: δ = 0.
  Eigen::MatrixXd xi(2, 2);
  xi << 1.0, -1.0, 1.0, 1.0;
  fo::LinearConstraints k;
  k.A_in = Eigen::MatrixXd{{0.0, -1.0}};
  k.b_in = Eigen::VectorXd::Zero(1);
  const auto c = fo::stationarity_certificate(xi, Eigen::Vector2d::Zero(), k);
  EXPECT_NEAR(c.distance, 0.0, kTol);
  EXPECT_LE((c.normal_part - Eigen::Vector2d(0.0, -1.0)).norm(), kTol);
  EXPECT_NEAR(c.distance, (c.subgradient_part + c.normal_part).norm(), kTol);
}

TEST(StationarityCertificate, MergesDuplicateSubgradients) {
  const auto c = fo::stationarity_certificate(pieces({2.0, 2.0, 2.0, 3.0}), Eigen::VectorXd::Zero(1));
  EXPECT_EQ(c.num_distinct_subgradients, 2);
  EXPECT_NEAR(c.distance, 2.0, kTol);
}

TEST(StationarityCertificate, RejectsMismatchedShapesAndInfeasiblePoints) {
  EXPECT_THROW((void)fo::stationarity_certificate(Eigen::MatrixXd::Ones(2, 3), Eigen::VectorXd::Zero(3)),
               frictopt::InvalidInput);
  EXPECT_THROW((void)fo::stationarity_certificate(Eigen::MatrixXd(1, 0), Eigen::VectorXd::Zero(1)),
               frictopt::InvalidInput);
  fo::LinearConstraints k;
  k.lower = Eigen::VectorXd::Zero(1);
  EXPECT_THROW((void)fo::stationarity_certificate(pieces({1.0}), Eigen::VectorXd::Constant(1, -1.0), k),
               frictopt::InvalidInput);
}

TEST(StationarityCertificate, IsHomogeneousInTheSubgradientsOverThirtyOrdersOfMagnitude) {
  // δ(cΞ) = c·δ(Ξ) with the constraint normals unchanged (N_Υ is a cone). Unscaled, the QP's
  // Hessian ΞᵀΞ next to unit normals failed for ‖ξ‖ ~ 1e15; the certificate must
  // return a status and the homogeneous value, never NaN.
  Eigen::MatrixXd xi(2, 3);
  xi << 1.0, -1.0, 0.5, -2.0, -2.5, -3.0;  // all descend along +x2: blocked only by x2 <= 0
  fo::LinearConstraints k;
  k.upper = Eigen::Vector2d(10.0, 0.0);
  const Eigen::Vector2d x(0.3, 0.0);
  const auto ref = fo::stationarity_certificate(xi, x, k);
  ASSERT_EQ(ref.status, frictopt::Status::kConverged) << ref.brief_report();
  EXPECT_NEAR(ref.distance, 0.0, kTol);  // 0 ∈ conv{ξ} + cone{e_2}: θ on ξ1, ξ2 cancels x1
  Eigen::MatrixXd off = xi;
  off.row(0).array() += 1.0;  // x1-components 2, 0, 1.5: δ = 0 still (ξ2 has zero x1 part)
  off(0, 1) = 0.5;            // now all x1-components > 0: δ = min over the hull of the x1 part
  const auto ref_off = fo::stationarity_certificate(off, x, k);
  ASSERT_EQ(ref_off.status, frictopt::Status::kConverged);
  EXPECT_NEAR(ref_off.distance, 0.5, kTol);  // the smallest x1-component; x2 absorbed by N_Υ
  for (const double c : {1e-15, 1e-8, 1e8, 1e15}) {
    const auto s = fo::stationarity_certificate(c * off, x, k);
    ASSERT_EQ(s.status, frictopt::Status::kConverged) << "scale " << c << ": " << s.brief_report();
    ASSERT_TRUE(std::isfinite(s.distance)) << "scale " << c;
    // Relative round-off of one QP on the rescaled (O(1)) data.
    EXPECT_NEAR(s.distance / c, ref_off.distance, kTol) << "scale " << c;
    EXPECT_NEAR(s.weights.sum(), 1.0, kTol);
  }
}
