// SPDX-License-Identifier: MIT
// FloatingCoulombSolver (docs/experiments.md §5) on problems solvable by hand: one 3D node whose
// net force is prescribed (E = I): inside the friction set z = e and β makes the kinematics
// consistent; outside it the equality cannot hold and the solver says "no equilibrium" instead of
// iterating forever; bad options and sizes are InvalidInput.
#include "frictopt/contact/floating_coulomb_solver.hpp"

#include <gtest/gtest.h>

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
