// SPDX-License-Identifier: MIT
#include "frictopt/shape/bezier_shape.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/finite_difference.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/shape/admissible_set.hpp"
#include "frictopt/shape/bernstein.hpp"

namespace frictopt::shape {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

TEST(BernsteinBasis, SumsToOneAndIsNonNegativeOnUnitInterval) {
  for (int degree : {0, 1, 2, 5, 14})
    for (double t = 0.0; t <= 1.0; t += 0.0625) {
      const Eigen::VectorXd b = bernstein_basis(degree, t);
      EXPECT_NEAR(b.sum(), 1.0, 20 * kEps) << "degree " << degree << " t " << t;
      EXPECT_GE(b.minCoeff(), 0.0);
    }
}

TEST(BernsteinBasis, MatchesClosedForm) {
  const int degree = 6;
  const double t = 0.3;
  const Eigen::VectorXd b = bernstein_basis(degree, t);
  for (int i = 0; i <= degree; ++i) {
    const double binom = std::tgamma(degree + 1) / (std::tgamma(i + 1) * std::tgamma(degree - i + 1));
    EXPECT_NEAR(b(i), binom * std::pow(t, i) * std::pow(1 - t, degree - i), 50 * kEps);
  }
}

TEST(BernsteinBasis, DerivativeMatchesCentralDifferences) {
  const double h = std::cbrt(kEps);
  for (int degree : {1, 3, 14})
    for (double t : {0.0 + h, 0.2, 0.5, 0.77, 1.0 - h}) {
      const Eigen::VectorXd fd =
          (bernstein_basis(degree, t + h) - bernstein_basis(degree, t - h)) / (2 * h);
      // Truncation error h²/6·|b'''| with |b'''| <= degree³·2^degree-ish; 1e-7 absolute is ample.
      EXPECT_LE((fd - bernstein_basis_derivative(degree, t)).cwiseAbs().maxCoeff(), 1e-6 * degree * degree)
          << "degree " << degree << " t " << t;
    }
}

TEST(BezierShape, EndValuesAreEndControlPoints2D) {
  const auto curve = BezierShape::curve(2.0, 15);
  Eigen::VectorXd alpha = Eigen::VectorXd::LinSpaced(15, 0.1, 0.8);
  EXPECT_NEAR(curve.height(alpha, Eigen::VectorXd::Constant(1, 0.0)), 0.1, 1e-15);
  EXPECT_NEAR(curve.height(alpha, Eigen::VectorXd::Constant(1, 2.0)), 0.8, 1e-15);
}

TEST(BezierShape, IntegralWeightsMatchGaussQuadrature) {
  // Each Bernstein polynomial integrates to a/d (docs/theory/problem.md §2; a=2, d=15: 0.1333...).
  const auto curve = BezierShape::curve(2.0, 15);
  EXPECT_NEAR(curve.integral_weights()(3), 2.0 / 15.0, 1e-15);
  const auto surface = BezierShape::surface(1.5, 0.5, 4, 3);
  // 8-point Gauss–Legendre per direction integrates degree <= 15 exactly.
  const double gx[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                        -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                        0.7966664774136267,  0.9602898564975363};
  const double gw[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                        0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                        0.2223810344533745, 0.1012285362903763};
  Eigen::VectorXd integral = Eigen::VectorXd::Zero(12);
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) {
      Eigen::Vector2d x(0.75 * (1 + gx[i]), 0.25 * (1 + gx[j]));
      integral += gw[i] * gw[j] * 0.75 * 0.25 * surface.basis(x);
    }
  EXPECT_LE((integral - surface.integral_weights()).norm(), 1e-14);
}

TEST(BezierShape, SurfaceOrdersControlsWithX1Fastest) {
  const auto surface = BezierShape::surface(1.0, 1.0, 3, 4);
  // At the corner (a, 0) only control (i=2, j=0), index 2 + 3·0 = 2, is active.
  const Eigen::VectorXd row = surface.basis(Eigen::Vector2d(1.0, 0.0));
  EXPECT_NEAR(row(2), 1.0, 1e-15);
  EXPECT_NEAR(row.sum(), 1.0, 1e-15);
  // At (0, b): control (0, 3), index 9.
  EXPECT_NEAR(surface.basis(Eigen::Vector2d(0.0, 1.0))(9), 1.0, 1e-15);
}

TEST(BezierShape, SlopeMatchesCentralDifferences) {
  const auto surface = BezierShape::surface(1.2, 0.8, 4, 3);
  const double h = std::cbrt(kEps);
  const Eigen::Vector2d x(0.37, 0.51);
  for (int c = 0; c < 2; ++c) {
    Eigen::Vector2d e = Eigen::Vector2d::Zero();
    e(c) = h;
    const Eigen::VectorXd fd = (surface.basis(x + e) - surface.basis(x - e)) / (2 * h);
    EXPECT_LE((fd - surface.basis_derivative(x, c)).norm(), 1e-8) << "direction " << c;
  }
}

TEST(BezierShape, GapMatrixRowsAreBases) {
  const auto curve = BezierShape::curve(2.0, 5);
  Eigen::MatrixXd points(3, 1);
  points << 0.0, 0.7, 2.0;
  const Eigen::MatrixXd B = curve.gap_matrix(points);
  EXPECT_EQ(B.rows(), 3);
  EXPECT_LE((B.row(1).transpose() - curve.basis(Eigen::VectorXd::Constant(1, 0.7))).norm(), 1e-15);
  EXPECT_LE((B.rowwise().sum() - Eigen::VectorXd::Ones(3)).norm(), 1e-14);
}

TEST(BezierShape, RejectsTooFewControlPoints) {
  EXPECT_THROW((void)BezierShape::curve(1.0, 1), InvalidInput);
  EXPECT_THROW((void)BezierShape::surface(1.0, 1.0, 2, 1), InvalidInput);
  EXPECT_THROW((void)BezierShape::curve(-1.0, 4), InvalidInput);
}

TEST(AdmissibleSet, ThesisExampleHas58InequalitiesAndCorrectedVolume) {
  // Thesis §5.2 data with the corrected volume (docs/theory/problem.md §6): d = 15, C0 = 0.75,
  // C1 = 1, C2 = 1.9, a = 2, C4 = 1: 2(d−1) slope rows and Σα = d(C4 − C2/a) = 0.75; bounds are
  // kept apart as lower/upper vectors (2d = 30 more).
  const auto curve = BezierShape::curve(2.0, 15);
  AdmissibleSetParameters p;
  p.upper_bound = 0.75;
  p.slope_bound = 1.0;
  p.volume = 1.9;
  p.height = 1.0;
  const LinearConstraints c = make_admissible_set(curve, p);
  EXPECT_EQ(c.A_in.rows() + 2 * c.dimension(), 58);
  ASSERT_EQ(c.A_eq.rows(), 1);
  EXPECT_NEAR(c.b_eq(0), 0.75, 1e-14);
  EXPECT_NEAR(c.b_in(0), 1.0 / 14.0, 1e-15);
  const Eigen::VectorXd flat = Eigen::VectorXd::Constant(15, 0.05);  // A-INIT
  EXPECT_LE(c.max_violation(flat), 1e-14);
  Eigen::VectorXd steep = flat;
  steep(3) += 0.2;
  steep(4) -= 0.2;
  EXPECT_NE(c.describe_violation(steep, 1e-12).find("slope"), std::string::npos)
      << c.describe_violation(steep, 1e-12);
}

TEST(AdmissibleSet, ThreeDimensionalSlopesInBothDirections) {
  const auto surface = BezierShape::surface(1.0, 2.0, 3, 4);
  AdmissibleSetParameters p;
  p.upper_bound = 0.2;
  p.slope_bound = 0.3;
  p.volume = 2.0 * 1.0 - 0.1 * 2.0;  // mean height 0.1
  p.height = 1.0;
  p.slope_scaling = SlopeScaling::kExact;
  const LinearConstraints c = make_admissible_set(surface, p);
  // x1 pairs: (3−1)·4 = 8, x2 pairs: 3·(4−1) = 9; two rows each.
  EXPECT_EQ(c.A_in.rows(), 2 * (8 + 9));
  EXPECT_NEAR(c.b_eq(0), 12 * 0.1, 1e-14);
  EXPECT_NEAR(c.b_in(0), 1.0 * 0.3 / 2, 1e-15);   // x1: a·C1/(m1−1)
  EXPECT_NEAR(c.b_in(16), 2.0 * 0.3 / 3, 1e-15);  // x2: b·C1/(m2−1)
}

TEST(AdmissibleSet, RejectsAnEmptyVolumeConstraintWithAClearMessage) {
  const auto curve = BezierShape::curve(2.0, 15);
  AdmissibleSetParameters p;
  p.upper_bound = 0.75;
  p.volume = 28.5;  // the thesis' printed Σα = C2·d reading: empty set
  p.height = 1.0;
  try {
    (void)make_admissible_set(curve, p);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("design.volume"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace frictopt::shape
