// SPDX-License-Identifier: MIT
// The geometry a friction law owns (FrictionLaw::gauge, radial, projection_jacobian,
// exposed_point_jacobian, exposed_point_orientation_derivative, the coefficients and their
// derivatives, is_isotropic) for every kind, turned and anisotropic ones included: the
// Jacobians against central differences of project / exposed_point / rotated /
// with_coefficients, and the gauge against the support function and the boundary.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "common/finite_difference.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::contact {
namespace {

constexpr std::uint64_t kSeed = 20261128;

struct LawCase {
  std::string name;
  FrictionLaw law;
};

std::vector<LawCase> laws_3d() {
  return {{"disc", FrictionLaw::disc(0.3)},
          {"disc turned", FrictionLaw::disc(0.3).rotated(0.4)},
          {"regular_polygon8", FrictionLaw::regular_polygon(0.3, 8)},
          {"polygon6", FrictionLaw::polygon({0.2, 0.35, 0.5, 0.45, 0.3, 0.25})},
          {"polygon6 turned", FrictionLaw::polygon({0.2, 0.35, 0.5, 0.45, 0.3, 0.25}).rotated(-0.7)},
          {"ellipse", FrictionLaw::ellipse(0.2, 0.6)},
          {"ellipse turned", FrictionLaw::ellipse(0.2, 0.6).rotated(0.9)},
          {"ellipse_polygon12 turned", FrictionLaw::ellipse_polygon(0.2, 0.6, 12).rotated(0.3)}};
}

std::vector<LawCase> all_laws() {
  std::vector<LawCase> laws = laws_3d();
  laws.push_back({"interval", FrictionLaw::interval(0.2, 0.5)});
  return laws;
}

Eigen::Vector2d unit(double theta) { return {std::cos(theta), std::sin(theta)}; }

// A random tangential vector of the law's dimension (2D: component 1 = 0).
Eigen::Vector2d random_vector(const FrictionLaw& law, std::mt19937_64& rng, double scale) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Vector2d v(normal(rng), law.dim() == 3 ? normal(rng) : 0.0);
  return scale * v;
}

// The shared checker's central-difference Jacobian of a map f: R² → R² at x
// along the law's tangential components (2D: component 0 only), with h = cbrt(eps)·max(1, |x|).
template <class F>
Eigen::Matrix2d central_difference(const F& f, const Eigen::Vector2d& x, int components) {
  const Eigen::VectorXd head = x.head(components);
  const auto g = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    Eigen::Vector2d full = x;
    full.head(components) = v;
    return f(full);
  };
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  J.leftCols(components) = testing::central_jacobian(g, head, testing::central_step(head));
  return J;
}

TEST(FrictionLawGeometry, GaugeIsOneOnTheBoundaryAndHomogeneous) {
  std::mt19937_64 rng{kSeed};
  std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi), scale(0.1, 3.0);
  for (const LawCase& c : all_laws()) {
    const double mu = c.law.max_coefficient();
    for (int trial = 0; trial < 100; ++trial) {
      const Eigen::Vector2d d = c.law.dim() == 3 ? unit(angle(rng)) : Eigen::Vector2d(trial % 2 ? 1.0 : -1.0, 0.0);
      // ρ(d)·d is on the boundary: gauge 1, boundary offset 0, fixed by the projection.
      const Eigen::Vector2d b = c.law.radial(d) * d;
      EXPECT_NEAR(c.law.gauge(b), 1.0, 1e-14) << c.name;
      EXPECT_NEAR(c.law.boundary_offset(b, 1.0), 0.0, 1e-14 * mu) << c.name;
      EXPECT_LE((c.law.project(b, 1.0) - b).norm(), 1e-14 * mu) << c.name;
      // The projection of an outside point lands on the boundary; the exposed point too.
      const Eigen::Vector2d far = 3.0 * mu * d;
      EXPECT_NEAR(c.law.gauge(c.law.project(far, 1.0)), 1.0, 1e-13) << c.name << " d = " << d.transpose();
      EXPECT_NEAR(c.law.gauge(c.law.exposed_point(d)), 1.0, 1e-13) << c.name << " d = " << d.transpose();
      // Positive homogeneity and the membership test x ∈ sW ⇔ γ(x) <= s.
      const Eigen::Vector2d x = random_vector(c.law, rng, mu);
      const double t = scale(rng);
      EXPECT_NEAR(c.law.gauge(t * x), t * c.law.gauge(x), 1e-13 * t * c.law.gauge(x)) << c.name;
      const double s = scale(rng);
      if (std::abs(c.law.gauge(x) - s) > 1e-9) {
        EXPECT_EQ(c.law.gauge(x) <= s, (c.law.project(x, s) - x).norm() <= 1e-15 * mu) << c.name;
      }
    }
  }
  const FrictionLaw zero = FrictionLaw::polygon({0.0, 0.0, 0.0});
  EXPECT_EQ(zero.gauge(Eigen::Vector2d::Zero()), 0.0);
  EXPECT_EQ(zero.gauge(Eigen::Vector2d(0.1, 0.0)), std::numeric_limits<double>::infinity());
}

TEST(FrictionLawGeometry, SupportIsTheMaximumOverTheBoundary) {
  std::mt19937_64 rng{kSeed + 1};
  std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
  constexpr int kSamples = 20000;
  for (const LawCase& c : laws_3d()) {
    // The boundary as ρ(θ)(cos θ, sin θ) on a fine grid, plus the polygons' vertices (where the
    // maximum of a linear function over a polygon is attained).
    std::vector<Eigen::Vector2d> boundary;
    for (int k = 0; k < kSamples; ++k) {
      const Eigen::Vector2d d = unit(2.0 * std::numbers::pi * k / kSamples);
      boundary.push_back(c.law.radial(d) * d);
    }
    for (const Eigen::Vector2d& w : c.law.vertices()) boundary.push_back(w);
    const double mu = c.law.max_coefficient();
    for (int trial = 0; trial < 50; ++trial) {
      const Eigen::Vector2d u = unit(angle(rng));
      double best = -std::numeric_limits<double>::infinity();
      for (const Eigen::Vector2d& b : boundary) best = std::max(best, b.dot(u));
      // No boundary point beats N_W(u); the grid comes within O(Δθ²)·μ of it (Δθ = 3e-4, times the aspect ratio squared).
      EXPECT_LE(best, c.law.support(u) + 1e-14 * mu) << c.name;
      EXPECT_GE(best, c.law.support(u) - 1e-5 * mu) << c.name << " u = " << u.transpose();
      EXPECT_NEAR(c.law.exposed_point(u).dot(u), c.law.support(u), 1e-14 * mu) << c.name;
    }
  }
  const FrictionLaw interval = FrictionLaw::interval(0.2, 0.5);
  EXPECT_DOUBLE_EQ(interval.radial(Eigen::Vector2d(2.0, 0.0)), 0.25);
  EXPECT_DOUBLE_EQ(interval.radial(Eigen::Vector2d(-1.0, 0.0)), 0.2);
  EXPECT_DOUBLE_EQ(interval.support(Eigen::Vector2d(-1.0, 0.0)), 0.2);
}

TEST(FrictionLawGeometry, ProjectionJacobianMatchesCentralDifferences) {
  std::mt19937_64 rng{kSeed + 2};
  for (const LawCase& c : all_laws()) {
    const double mu = c.law.max_coefficient();
    int compared = 0, outside = 0;
    for (int trial = 0; trial < 300; ++trial) {
      const Eigen::Vector2d y = random_vector(c.law, rng, mu);
      const FrictionLaw::ProjectionJacobian p = c.law.projection_jacobian(y);
      ASSERT_LE((p.point - c.law.project(y, 1.0)).norm(), 1e-15 * mu) << c.name;
      // The projection is piecewise smooth: a pair whose sides lie on different faces (the
      // second difference jumps by O(h)) is skipped, the check is at smooth points only.
      const double h = testing::central_step(y);
      const auto project = [&](const Eigen::Vector2d& x) -> Eigen::VectorXd { return c.law.project(x, 1.0); };
      bool smooth = true;
      for (int k = 0; k < c.law.tangential_dim(); ++k) {
        const Eigen::Vector2d e = Eigen::Vector2d::Unit(k) * h;
        if (((project(y + e) - p.point) - (p.point - project(y - e))).norm() > 1e-3 * h) smooth = false;
      }
      if (!smooth) continue;
      ++compared;
      if (p.face.face != FrictionFace::kInterior) ++outside;
      const Eigen::Matrix2d fd = central_difference(project, y, c.law.tangential_dim());
      // Truncation ~h²/r², h = 6e-6, r >= μ_min²/μ_max = 0.067 the smallest curvature radius
      // (the ellipse): ~1e-8; rounding eps/h ~ 4e-11. 1e-6 on entries of size <= 1.
      EXPECT_LE((p.jacobian - fd).norm(), 1e-6) << c.name << " y = " << y.transpose() << " face "
                                                << to_string(p.face.face);
      // J is symmetric with eigenvalues in [0, 1] (the derivative of a projection onto a convex set).
      EXPECT_LE((p.jacobian - p.jacobian.transpose()).norm(), 1e-14) << c.name;
    }
    EXPECT_GE(compared, 200) << c.name << ": too few smooth sample points";
    EXPECT_GE(outside, 50) << c.name << ": too few sample points outside W";
  }
}

TEST(FrictionLawGeometry, ProjectionJacobianNamesTheFace) {
  const FrictionLaw square = FrictionLaw::regular_polygon(1.0, 4);  // vertices at ±45°, ±135°
  const FrictionLaw::ProjectionJacobian edge = square.projection_jacobian(Eigen::Vector2d(2.0, 0.1));
  EXPECT_EQ(edge.face.face, FrictionFace::kEdge);
  EXPECT_NEAR((edge.jacobian - Eigen::Vector2d(0, 1) * Eigen::Vector2d(0, 1).transpose()).norm(), 0.0, 1e-14);
  const FrictionLaw::ProjectionJacobian corner = square.projection_jacobian(Eigen::Vector2d(3.0, 3.0));
  EXPECT_EQ(corner.face.face, FrictionFace::kVertex);
  EXPECT_EQ(corner.jacobian, Eigen::Matrix2d::Zero());
  EXPECT_EQ(FrictionLaw::ellipse(0.2, 0.4).projection_jacobian(Eigen::Vector2d(1, 1)).face.face, FrictionFace::kSmooth);
  EXPECT_EQ(FrictionLaw::disc(0.2).projection_jacobian(Eigen::Vector2d(0.1, 0)).face.face, FrictionFace::kInterior);
  EXPECT_EQ(FrictionLaw::disc(0.0).projection_jacobian(Eigen::Vector2d(0.1, 0)).face.face, FrictionFace::kDegenerate);
}

TEST(FrictionLawGeometry, ExposedPointJacobianMatchesCentralDifferences) {
  std::mt19937_64 rng{kSeed + 3};
  for (const LawCase& c : all_laws()) {
    const int nt = c.law.tangential_dim();
    int compared = 0;
    for (int trial = 0; trial < 200; ++trial) {
      const Eigen::Vector2d u = random_vector(c.law, rng, 1.0);
      const double h = testing::central_step(u);
      const auto w = [&](const Eigen::Vector2d& v) -> Eigen::VectorXd { return c.law.exposed_point(v); };
      // A polygon's exposed point jumps across an edge-normal ray: skip a pair that straddles one.
      if (c.law.is_polygonal() && (w(u + Eigen::Vector2d::Unit(0) * h) != w(u - Eigen::Vector2d::Unit(0) * h) ||
                                   (nt == 2 && w(u + Eigen::Vector2d::Unit(1) * h) != w(u - Eigen::Vector2d::Unit(1) * h))))
        continue;
      ++compared;
      const Eigen::Matrix2d fd = central_difference(w, u, nt);
      EXPECT_LE((c.law.exposed_point_jacobian(u) - fd).norm(), 1e-6 * c.law.max_coefficient() / u.norm())
          << c.name << " u = " << u.transpose();
      // ∂w/∂u u = 0: w is 0-homogeneous in u.
      EXPECT_LE((c.law.exposed_point_jacobian(u) * u).norm(), 1e-14) << c.name;
    }
    EXPECT_GE(compared, 150) << c.name;
  }
  EXPECT_EQ(FrictionLaw::ellipse(0.2, 0.4).exposed_point_jacobian(Eigen::Vector2d::Zero()), Eigen::Matrix2d::Zero());
}

TEST(FrictionLawGeometry, OrientationDerivativeMatchesCentralDifferences) {
  std::mt19937_64 rng{kSeed + 4};
  constexpr double h = 1e-6;
  for (const LawCase& c : laws_3d()) {
    int compared = 0;
    for (int trial = 0; trial < 100; ++trial) {
      const Eigen::Vector2d u = random_vector(c.law, rng, 1.0);
      const Eigen::Vector2d plus = c.law.rotated(h).exposed_point(u), minus = c.law.rotated(-h).exposed_point(u);
      // A polygon's turn moves an edge-normal ray across u now and then: skip that pair.
      if (c.law.is_polygonal() && (plus - minus).norm() > 1e-3) continue;
      ++compared;
      const Eigen::Vector2d fd = (plus - minus) / (2.0 * h);
      EXPECT_LE((c.law.exposed_point_orientation_derivative(u) - fd).norm(), 1e-7) << c.name << " u = " << u.transpose();
    }
    EXPECT_GE(compared, 80) << c.name;
    if (c.law.is_isotropic()) {
      EXPECT_LE(c.law.exposed_point_orientation_derivative(Eigen::Vector2d(0.3, -0.8)).norm(), 1e-15) << c.name;
    }
  }
}

TEST(FrictionLawGeometry, CoefficientDerivativesMatchCentralDifferences) {
  std::mt19937_64 rng{kSeed + 5};
  constexpr double h = 1e-6;
  for (const LawCase& c : all_laws()) {
    const Eigen::VectorXd coefficients = c.law.coefficients();
    const auto nc = coefficients.size();
    ASSERT_EQ(static_cast<std::size_t>(nc), c.law.coefficient_names().size()) << c.name;
    const auto law_at = [&](Eigen::Index k, double step) {
      Eigen::VectorXd values = coefficients;
      values(k) += step;
      return c.law.with_coefficients(values, c.law.orientation());
    };
    // The vertices' derivatives (polygons and the interval).
    const auto dv = c.law.vertex_coefficient_derivatives();
    ASSERT_EQ(dv.size(), c.law.is_polygonal() ? static_cast<std::size_t>(nc) : 0u) << c.name;
    for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(dv.size()); ++k) {
      const FrictionLaw plus = law_at(k, h), minus = law_at(k, -h);
      for (std::size_t j = 0; j < c.law.vertices().size(); ++j) {
        const Eigen::Vector2d fd = (plus.vertices()[j] - minus.vertices()[j]) / (2.0 * h);
        EXPECT_LE((dv[static_cast<std::size_t>(k)][j] - fd).norm(), 1e-8) << c.name << " k = " << k << " j = " << j;
      }
    }
    // The exposed point's derivative at fixed u.
    for (int trial = 0; trial < 50; ++trial) {
      const Eigen::Vector2d u = random_vector(c.law, rng, 1.0);
      const Eigen::MatrixXd J = c.law.exposed_point_coefficient_jacobian(u);
      ASSERT_EQ(J.rows(), 2);
      ASSERT_EQ(J.cols(), nc);
      for (Eigen::Index k = 0; k < nc; ++k) {
        const Eigen::Vector2d fd = (law_at(k, h).exposed_point(u) - law_at(k, -h).exposed_point(u)) / (2.0 * h);
        if (c.law.is_polygonal() && fd.norm() > 10.0) continue;  // the exposed vertex changed
        EXPECT_LE((J.col(k) - fd).norm(), 1e-7) << c.name << " k = " << k << " u = " << u.transpose();
      }
    }
  }
}

TEST(FrictionLawGeometry, WithCoefficientsRebuildsTheLaw) {
  std::mt19937_64 rng{kSeed + 6};
  for (const LawCase& c : all_laws()) {
    const FrictionLaw back = c.law.with_coefficients(c.law.coefficients(), c.law.orientation());
    EXPECT_EQ(back.kind(), c.law.kind()) << c.name;
    EXPECT_EQ(back.orientation(), c.law.orientation()) << c.name;
    EXPECT_EQ(back.vertices().size(), c.law.vertices().size()) << c.name;
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::Vector2d u = random_vector(c.law, rng, 1.0);
      EXPECT_NEAR(back.support(u), c.law.support(u), 1e-15 * u.norm() + 1e-15) << c.name;
    }
    EXPECT_THROW((void)c.law.with_coefficients(Eigen::VectorXd::Zero(c.law.coefficients().size() + 1), 0.0),
                 InvalidInput)
        << c.name;
  }
}

TEST(FrictionLawGeometry, IsotropyMeansEveryTurnLeavesTheSetUnchanged) {
  const std::vector<LawCase> isotropic{{"disc", FrictionLaw::disc(0.3)},
                                       {"disc turned", FrictionLaw::disc(0.3).rotated(1.1)},
                                       {"round ellipse", FrictionLaw::ellipse(0.25, 0.25).rotated(0.2)},
                                       {"zero polygon", FrictionLaw::polygon({0.0, 0.0, 0.0, 0.0})}};
  const std::vector<LawCase> anisotropic{{"ellipse", FrictionLaw::ellipse(0.2, 0.3)},
                                         {"regular_polygon8", FrictionLaw::regular_polygon(0.3, 8)},
                                         {"round ellipse_polygon", FrictionLaw::ellipse_polygon(0.3, 0.3, 8)},
                                         {"polygon4", FrictionLaw::polygon({0.3, 0.5, 0.3, 0.5})}};
  const std::vector<double> turns{0.1, 0.5, 1.3, 2.9};
  const std::vector<Eigen::Vector2d> directions{unit(0.0), unit(0.3), unit(1.0), unit(2.2), unit(4.0)};
  const auto largest_change = [&](const FrictionLaw& law) {
    double change = 0.0;
    for (double phi : turns)
      for (const Eigen::Vector2d& u : directions) change = std::max(change, std::abs(law.rotated(phi).support(u) - law.support(u)));
    return change;
  };
  for (const LawCase& c : isotropic) {
    EXPECT_TRUE(c.law.is_isotropic()) << c.name;
    EXPECT_LE(largest_change(c.law), 1e-15) << c.name;
  }
  for (const LawCase& c : anisotropic) {
    EXPECT_FALSE(c.law.is_isotropic()) << c.name;
    EXPECT_GT(largest_change(c.law), 1e-4) << c.name;
  }
  EXPECT_TRUE(FrictionLaw::interval(0.3, 0.3).is_isotropic());
  EXPECT_FALSE(FrictionLaw::interval(0.2, 0.3).is_isotropic());
}

}  // namespace
}  // namespace frictopt::contact
