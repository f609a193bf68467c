// SPDX-License-Identifier: MIT
// Turned friction laws (FrictionLaw::rotated, docs/theory/friction-frame.md §1): every method of
// the turned law equals the unturned law's conjugated by the rotation, a regular n-gon is invariant
// under a turn by 2π/n, and a contact problem turned about the normal (law, tangential loads and
// the tangential blocks of M) has the same λ and turned q.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "contact_test_problems.hpp"
#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/linalg/linear_operator.hpp"

namespace frictopt::contact {
namespace {

Eigen::Matrix2d rotation(double phi) {
  Eigen::Matrix2d r;
  r << std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi);
  return r;
}

std::vector<FrictionLaw> laws_3d() {
  return {FrictionLaw::disc(0.4),
          FrictionLaw::regular_polygon(0.4, 8),
          FrictionLaw::polygon({0.3, 0.5, 0.3, 0.5}),
          FrictionLaw::polygon({0.2, 0.35, 0.5, 0.45, 0.3, 0.25}),
          FrictionLaw::ellipse(0.2, 0.6),
          FrictionLaw::ellipse_polygon(0.2, 0.6, 16)};
}

// W_φ = R W: project_φ(q) = R project(Rᵀq), N_φ(u) = N(Rᵀu), w_φ(u) = R w(Rᵀu), and the
// step, offset and faces of (Rq, Rd) equal those of (q, d). Rounding of the rotation (a few
// ulps of |q|) is the only difference: 1e-13 relative to the set's size.
TEST(RotatedFrictionLaw, EveryMethodIsTheUnturnedOneConjugatedByTheRotation) {
  std::mt19937_64 rng{testing::kSeed};
  std::normal_distribution<double> normal(0.0, 0.5);
  for (const FrictionLaw& law : laws_3d()) {
    for (const double phi : {0.3, -1.1, 2.5}) {
      const FrictionLaw turned = law.rotated(phi);
      const Eigen::Matrix2d R = rotation(phi);
      SCOPED_TRACE(turned.describe());
      EXPECT_NEAR(turned.orientation(), phi, 0.0);
      EXPECT_LE((turned.frame() - R).norm(), 1e-15);
      const double tol = 1e-13 * law.max_coefficient();
      for (int trial = 0; trial < 200; ++trial) {
        const Eigen::Vector2d q(normal(rng), normal(rng)), u(normal(rng), normal(rng)), d(normal(rng), normal(rng));
        const double s = 0.5 + std::abs(normal(rng));
        const Eigen::Vector2d rq = R * q, ru = R * u, rd = R * d;
        EXPECT_LE((turned.project(rq, s) - R * law.project(q, s)).norm(), tol * s);
        EXPECT_NEAR(turned.support(ru), law.support(u), tol * u.norm());
        EXPECT_LE((turned.exposed_point(ru) - R * law.exposed_point(u)).norm(), tol);
        EXPECT_NEAR(turned.boundary_offset(rq, s), law.boundary_offset(q, s), tol * s);
        // max_step from a point of s·W (its projection).
        const Eigen::Vector2d inside = 0.7 * law.project(q, s);
        const double step = law.max_step(inside, s, d);
        EXPECT_NEAR(turned.max_step(R * inside, s, rd), step, 1e-12 * step);
        // Faces: a boundary point and a slip direction keep their face and index.
        const Eigen::Vector2d on_boundary = law.project(3.0 * q, s);
        EXPECT_EQ(turned.locate(R * on_boundary, s, 1e-10), law.locate(on_boundary, s, 1e-10));
        EXPECT_EQ(turned.sector(ru, 1e-8), law.sector(u, 1e-8));
        const ClassificationTolerance t{1e-10, 1e-12, 1e-8};
        const FrictionClassification a = turned.classify(R * on_boundary, s, ru, t), b = law.classify(on_boundary, s, u, t);
        EXPECT_EQ(a.force, b.force);
        EXPECT_EQ(a.slip, b.slip);
      }
      // Polygon data: vertices and normals turn, heights stay.
      for (std::size_t j = 0; j < law.vertices().size(); ++j)
        EXPECT_LE((turned.vertices()[j] - R * law.vertices()[j]).norm(), tol);
      for (std::size_t j = 0; j < law.edge_normals().size(); ++j) {
        EXPECT_LE((turned.edge_normals()[j] - R * law.edge_normals()[j]).norm(), 1e-15);
        EXPECT_EQ(turned.edge_heights()[j], law.edge_heights()[j]);
      }
      EXPECT_EQ(turned.semi_axes(), law.semi_axes());
    }
  }
}

// μ_φ(θ) = μ(θ − φ): the coefficient for sliding in direction θ (the support function of the
// unit direction) is the unturned law's at θ − φ.
TEST(RotatedFrictionLaw, DirectionalCoefficientIsShiftedByTheAngle) {
  const FrictionLaw law = FrictionLaw::ellipse(0.2, 0.6);
  const double phi = std::numbers::pi / 6;
  const FrictionLaw turned = law.rotated(phi);
  for (int k = 0; k < 36; ++k) {
    const double theta = 2 * std::numbers::pi * k / 36;
    const double mu = turned.support(Eigen::Vector2d(std::cos(theta), std::sin(theta)));
    const double expected = law.support(Eigen::Vector2d(std::cos(theta - phi), std::sin(theta - phi)));
    EXPECT_NEAR(mu, expected, 1e-15);
  }
  // Along the turned major axis the coefficient is μ_y.
  EXPECT_NEAR(turned.support(Eigen::Vector2d(-std::sin(phi), std::cos(phi))), 0.6, 1e-15);
}

// A regular n-gon turned by 2π/n is the same set: vertex j of the turned polygon is vertex j+1
// of the unturned one, and the projection is the same map.
TEST(RotatedFrictionLaw, RegularPolygonTurnedByItsSymmetryAngleIsUnchanged) {
  std::mt19937_64 rng{testing::kSeed + 1};
  std::normal_distribution<double> normal(0.0, 0.5);
  for (const int n : {3, 4, 8, 17}) {
    const FrictionLaw law = FrictionLaw::regular_polygon(0.35, n);
    const FrictionLaw turned = law.rotated(2 * std::numbers::pi / n);
    for (int j = 0; j < n; ++j)
      EXPECT_LE((turned.vertices()[static_cast<std::size_t>(j)] - law.vertices()[static_cast<std::size_t>((j + 1) % n)]).norm(),
                1e-15)
          << "n = " << n << ", vertex " << j;
    for (int trial = 0; trial < 100; ++trial) {
      const Eigen::Vector2d q(normal(rng), normal(rng));
      EXPECT_LE((turned.project(q, 1.0) - law.project(q, 1.0)).norm(), 1e-15);
      EXPECT_NEAR(turned.support(q), law.support(q), 1e-15);
    }
  }
}

TEST(RotatedFrictionLaw, OrientationsAddAndAreDescribed) {
  const FrictionLaw law = FrictionLaw::polygon({0.3, 0.5, 0.3, 0.5});
  const FrictionLaw twice = law.rotated(0.2).rotated(0.3);
  EXPECT_DOUBLE_EQ(twice.orientation(), 0.5);
  EXPECT_LE((twice.frame() - rotation(0.5)).norm(), 1e-15);
  for (std::size_t j = 0; j < 4; ++j) EXPECT_LE((twice.vertices()[j] - law.rotated(0.5).vertices()[j]).norm(), 1e-15);
  EXPECT_EQ(law.describe(), "polygon(n=4, mu=[0.3, 0.5, 0.3, 0.5])");
  EXPECT_EQ(law.rotated(std::numbers::pi / 6).describe(), "polygon(n=4, mu=[0.3, 0.5, 0.3, 0.5], orientation_deg=30)");
  EXPECT_EQ(FrictionLaw::ellipse(0.2, 0.4).rotated(-std::numbers::pi / 4).describe(),
            "ellipse(mu_x=0.2, mu_y=0.4, orientation_deg=-45)");
  EXPECT_EQ(law.rotated(0.0).orientation(), 0.0);
}

TEST(RotatedFrictionLaw, RefusesATurnedIntervalAndANonFiniteAngle) {
  const FrictionLaw interval = FrictionLaw::interval(0.2, 0.3);
  EXPECT_EQ(interval.rotated(0.0).describe(), interval.describe());
  try {
    (void)interval.rotated(0.1);
    ADD_FAILURE() << "a turned 2D law was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("angle = 0.1; expected 0"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)FrictionLaw::disc(0.3).rotated(std::nan("")), InvalidInput);
  EXPECT_THROW((void)FrictionLaw::disc(0.3).rotated(INFINITY), InvalidInput);
}

// The contact problem turned about the normal: law W → R W, tangential loads c_t → R c_t and the
// Delassus matrix M → P M Pᵀ (P turns each node's tangential pair: the same body with its
// tangential frame turned). Its solution is (R q, λ): λ equal and q turned, to 1e-10 relative
// (solver stops at 1e-14 relative increments; cond(M) ≈ 9).
TEST(RotatedFrictionLaw, TurningLawAndTangentialLoadTurnsTheContactForces) {
  constexpr Eigen::Index p = 20;
  for (const FrictionLaw& law : laws_3d()) {
    std::mt19937_64 rng{testing::kSeed + 7};
    const Eigen::MatrixXd m = testing::random_spd(3 * p, rng);
    const Eigen::VectorXd c = testing::random_c(3, p, rng);
    const double phi = 0.7;
    Eigen::MatrixXd P = Eigen::MatrixXd::Identity(3 * p, 3 * p);
    for (Eigen::Index i = 0; i < p; ++i) P.block(3 * i, 3 * i, 2, 2) = rotation(phi);
    const Eigen::MatrixXd m_turned = P * m * P.transpose();
    const Eigen::VectorXd c_turned = P * c;
    CoulombSolver::Options options;
    options.relative_tolerance = 1e-14;
    options.max_iterations = 200;
    options.tresca.relative_tolerance = 1e-14;
    options.tresca.max_iterations = 200000;
    const linalg::DenseOperator op(m), op_turned(m_turned);
    ContactState state, state_turned;
    const auto summary = CoulombSolver(op, law, options).solve(c, state);
    const auto summary_turned = CoulombSolver(op_turned, law.rotated(phi), options).solve(c_turned, state_turned);
    SCOPED_TRACE(law.describe());
    ASSERT_TRUE(summary.converged()) << summary.brief_report();
    ASSERT_TRUE(summary_turned.converged()) << summary_turned.brief_report();
    const double error = (state_turned.z - P * state.z).norm() / state.z.norm();
    std::printf("%s turned by %.2f: |z_φ − P z|/|z| = %.2e\n", law.describe().c_str(), phi, error);
    EXPECT_LE(error, 1e-10);
    EXPECT_LE((state_turned.normal_forces() - state.normal_forces()).norm(), 1e-10 * state.normal_forces().norm());
  }
}

}  // namespace
}  // namespace frictopt::contact
