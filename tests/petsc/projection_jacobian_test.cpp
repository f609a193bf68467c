// SPDX-License-Identifier: MIT
// The generalized Jacobian of the projection onto s·W against central differences of
// contact::FrictionLaw::project, for every law, at points where the projection is smooth.
#include "petsc/projection_jacobian.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace frictopt::petsc {
namespace {

constexpr std::uint64_t kSeed = 20261125;

struct LawCase {
  const char* name;
  contact::FrictionLaw law;
};

std::vector<LawCase> laws() {
  return {{"disc", contact::FrictionLaw::disc(0.3)},
          {"regular_polygon16", contact::FrictionLaw::regular_polygon(0.3, 16)},
          {"polygon4", contact::FrictionLaw::polygon({0.4, 0.2, 0.4, 0.2})},
          {"ellipse", contact::FrictionLaw::ellipse(0.4, 0.2)},
          {"ellipse_polygon", contact::FrictionLaw::ellipse_polygon(0.4, 0.2, 12)}};
}

TEST(ProjectionJacobian, MatchesCentralDifferencesForEveryLaw) {
  std::mt19937_64 rng{kSeed};
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> radius(0.2, 2.0);
  for (const LawCase& c : laws()) {
    int compared = 0;
    for (int trial = 0; trial < 200; ++trial) {
      const double s = radius(rng);
      const Eigen::Vector2d x = Eigen::Vector2d(normal(rng), normal(rng)) * 0.3 * s;
      const ProjectionLinearization lin = linearize_projection(c.law, x, s);
      ASSERT_LE((lin.value - c.law.project(x, s)).norm(), 1e-14 * s) << c.name;
      // Central differences with h = cbrt(eps)·scale; the projection is piecewise smooth, so
      // a pair whose two sides lie on different faces (|one-sided difference| mismatch) is
      // skipped: the check is at smooth points only.
      const double h = 6e-6 * s;
      Eigen::Matrix2d fd_x;
      bool smooth = true;
      for (int k = 0; k < 2; ++k) {
        const Eigen::Vector2d e = Eigen::Vector2d::Unit(k) * h;
        const Eigen::Vector2d plus = c.law.project(x + e, s), minus = c.law.project(x - e, s), mid = c.law.project(x, s);
        if (((plus - mid) - (mid - minus)).norm() > 1e-3 * h) smooth = false;  // a kink jumps by O(h)
        fd_x.col(k) = (plus - minus) / (2 * h);
      }
      const Eigen::Vector2d fd_s = (c.law.project(x, s + h) - c.law.project(x, s - h)) / (2 * h);
      if (!smooth) continue;
      ++compared;
      // Truncation O(h²·curvature) and rounding eps/h: 1e-6 absolute on O(1) derivatives.
      EXPECT_LE((lin.d_x - fd_x).norm(), 1e-6) << c.name << " x = " << x.transpose() << " s = " << s;
      EXPECT_LE((lin.d_s - fd_s).norm(), 1e-6) << c.name << " x = " << x.transpose() << " s = " << s;
    }
    EXPECT_GE(compared, 150) << c.name << ": too few smooth sample points";
  }
}

TEST(ProjectionJacobian, IntervalLawUsesOneComponent) {
  const contact::FrictionLaw law = contact::FrictionLaw::interval(0.2, 0.4);
  const ProjectionLinearization inside = linearize_projection(law, Eigen::Vector2d(0.1, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(inside.d_x(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(inside.d_s(0), 0.0);
  const ProjectionLinearization above = linearize_projection(law, Eigen::Vector2d(3.0, 0.0), 2.0);
  EXPECT_DOUBLE_EQ(above.value(0), 0.8);
  EXPECT_DOUBLE_EQ(above.d_x(0, 0), 0.0);
  EXPECT_DOUBLE_EQ(above.d_s(0), 0.4);
}

TEST(ProjectionJacobian, ZeroBoundGivesZero) {
  const ProjectionLinearization lin = linearize_projection(contact::FrictionLaw::disc(0.3), Eigen::Vector2d(1, 2), 0.0);
  EXPECT_EQ(lin.value, Eigen::Vector2d::Zero());
  EXPECT_EQ(lin.d_x, Eigen::Matrix2d::Zero());
}

}  // namespace
}  // namespace frictopt::petsc
