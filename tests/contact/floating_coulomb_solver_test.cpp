// SPDX-License-Identifier: MIT
// FloatingCoulombSolver (docs/experiments.md §5) on problems solvable by hand: one 3D node whose
// net force is prescribed (E = I): inside the friction set z = e and β makes the kinematics
// consistent; outside it the equality cannot hold and the solver says "no equilibrium" instead of
// iterating forever; bad options and sizes are InvalidInput.
#include "frictopt/contact/floating_coulomb_solver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include "frictopt/core/error.hpp"
#include "frictopt/linalg/linear_operator.hpp"

namespace frictopt::contact {
namespace {

TEST(FloatingCoulombSolver, NetForceInsideTheFrictionSetIsMet) {
  const linalg::DenseOperator M(Eigen::Matrix3d::Identity() * 2.0);
  const FloatingCoulombSolver solver(M, Eigen::Matrix3d::Identity(), FrictionLaw::disc(0.3), {});
  ContactState state;
  Eigen::VectorXd beta;
  const Eigen::VectorXd e = Eigen::Vector3d(0.1, -0.05, 1.0);  // (q, λ): |q| = 0.11 < 0.3·λ
  const Eigen::VectorXd c =
      Eigen::Vector3d(0.0, 0.0, 0.5);  // the free response (here a gap that would open)
  const auto summary = solver.solve(c, e, state, beta);
  ASSERT_TRUE(summary.converged()) << summary.brief_report();
  EXPECT_LE((state.z - e).norm(), 1e-9);
  // ∇ = Mz + c + Eᵀβ is the kinematics: λ > 0 closes the gap (∇_λ = 0), |q| < 0.3λ sticks (∇_q =
  // 0).
  EXPECT_LE((2.0 * state.z + c + beta).norm(), 1e-8);
  EXPECT_TRUE(state.is_stick(0));
}

TEST(FloatingCoulombSolver, NetForceOutsideTheFrictionSetHasNoEquilibrium) {
  const linalg::DenseOperator M(Eigen::Matrix3d::Identity());
  const FloatingCoulombSolver solver(M, Eigen::Matrix3d::Identity(), FrictionLaw::disc(0.3), {});
  ContactState state;
  Eigen::VectorXd beta;
  const auto summary =
      solver.solve(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.5, 0.0, 1.0), state, beta);
  EXPECT_EQ(summary.status, Status::kDiverged) << summary.brief_report();
  EXPECT_NE(summary.message.find("no equilibrium"), std::string::npos) << summary.message;
  EXPECT_GT(summary.equality_residual, 0.1);  // |q| stays at 0.3λ: the residual cannot vanish
}

// Four contact nodes of a random SPD Delassus matrix, balance rows for the net force (the three
// translations): the semismooth Newton method on (z, β) and the augmented Lagrangian (the
// fixed_point method) reach the same z and β, which meet the balance and the Coulomb conditions.
TEST(FloatingCoulombSolver, NewtonAndAugmentedLagrangianAgree) {
  const Eigen::Index p = 4, m = 3 * p;
  std::srand(3);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(m, m);
  const linalg::DenseOperator M(B * B.transpose() + 0.5 * Eigen::MatrixXd::Identity(m, m));
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(3, m);
  for (Eigen::Index i = 0; i < p; ++i)
    for (int k = 0; k < 3; ++k) E(k, 3 * i + k) = 1.0;
  const Eigen::VectorXd e = Eigen::Vector3d(0.4, -0.2, 4.0);  // |T| = 0.45 < 0.3 × 4
  const Eigen::VectorXd c = 0.3 * Eigen::VectorXd::Random(m);
  for (const FrictionLaw& law : {FrictionLaw::disc(0.3), FrictionLaw::polygon({0.3, 0.2, 0.35, 0.25})}) {
    SCOPED_TRACE(law.describe());
    FloatingCoulombSolver::Options newton, augmented;
    newton.coulomb.method = CoulombMethod::kSemismoothNewton;
    augmented.coulomb.method = CoulombMethod::kFixedPoint;
    augmented.coulomb.tresca.relative_tolerance = newton.coulomb.tresca.relative_tolerance = 1e-12;
    ContactState sn, sa;
    Eigen::VectorXd bn, ba;
    const auto rn = FloatingCoulombSolver(M, E, law, newton).solve(c, e, sn, bn);
    const auto ra = FloatingCoulombSolver(M, E, law, augmented).solve(c, e, sa, ba);
    ASSERT_TRUE(rn.converged()) << rn.brief_report();
    ASSERT_TRUE(ra.converged()) << ra.brief_report();
    EXPECT_TRUE(rn.solved_by_newton) << rn.brief_report();  // no fallback
    EXPECT_EQ(rn.outer_iterations, 0) << rn.brief_report();
    EXPECT_FALSE(ra.solved_by_newton) << ra.brief_report();
    EXPECT_GT(rn.newton_iterations, 0);
    EXPECT_GT(ra.outer_iterations, 0);
    EXPECT_LE((E * sn.z - e).norm(), 1e-9 * e.norm());
    EXPECT_LE((sn.z - sa.z).norm(), 1e-6 * sa.z.norm()) << sn.z.transpose() << "\n" << sa.z.transpose();
    EXPECT_LE((bn - ba).norm(), 1e-5 * std::max(1.0, ba.norm()));
    // The returned gradient is the kinematics with β: Mz + c + Eᵀβ.
    Eigen::VectorXd g(m);
    M.apply(sn.z, g);
    EXPECT_LE((g + c + E.transpose() * bn - sn.gradient).norm(), 1e-10 * std::max(1.0, g.norm()));
  }
}

// A warm start without β (the last design's state): β is fitted to the touching nodes and the
// Newton method converges from there in fewer steps than from the cold start.
TEST(FloatingCoulombSolver, WarmStartFitsTheMultiplier) {
  const Eigen::Index p = 5, m = 3 * p;
  std::srand(11);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(m, m);
  const linalg::DenseOperator M(B * B.transpose() + Eigen::MatrixXd::Identity(m, m));
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(3, m);
  for (Eigen::Index i = 0; i < p; ++i)
    for (int k = 0; k < 3; ++k) E(k, 3 * i + k) = 1.0;
  const Eigen::VectorXd e = Eigen::Vector3d(0.2, 0.1, 3.0);
  const Eigen::VectorXd c = 0.2 * Eigen::VectorXd::Random(m);
  FloatingCoulombSolver::Options o;
  o.coulomb.method = CoulombMethod::kSemismoothNewton;
  const FloatingCoulombSolver solver(M, E, FrictionLaw::disc(0.4), o);
  ContactState state;
  Eigen::VectorXd beta;
  const auto cold = solver.solve(c, e, state, beta);
  ASSERT_TRUE(cold.converged()) << cold.brief_report();
  Eigen::VectorXd warm_beta;  // the state alone carries over
  const Eigen::VectorXd e2 = 1.01 * e;
  const auto warm = solver.solve(c, e2, state, warm_beta);
  ASSERT_TRUE(warm.converged()) << warm.brief_report();
  EXPECT_TRUE(warm.solved_by_newton) << warm.brief_report();
  EXPECT_LE(warm.newton_iterations, cold.newton_iterations) << cold.brief_report() << "\n" << warm.brief_report();
  EXPECT_LE((E * state.z - e2).norm(), 1e-9 * e2.norm());
}

TEST(FloatingCoulombSolver, BadOptionsAndSizesAreInvalidInput) {
  const linalg::DenseOperator M(Eigen::Matrix3d::Identity());
  FloatingCoulombSolver::Options o;
  o.penalty_growth = 1.0;
  EXPECT_THROW(FloatingCoulombSolver(M, Eigen::Matrix3d::Identity(), FrictionLaw::disc(0.3), o),
               InvalidInput);
  EXPECT_THROW(
      FloatingCoulombSolver(M, Eigen::MatrixXd::Identity(2, 2), FrictionLaw::disc(0.3), {}),
      InvalidInput);
  const FloatingCoulombSolver solver(M, Eigen::Matrix3d::Identity(), FrictionLaw::disc(0.3), {});
  ContactState state;
  Eigen::VectorXd beta;
  EXPECT_THROW((void)solver.solve(Eigen::Vector3d::Zero(), Eigen::Vector2d::Zero(), state, beta),
               InvalidInput);
}

}  // namespace
}  // namespace frictopt::contact
