// SPDX-License-Identifier: MIT
#include "frictopt/optim/linear_constraints.hpp"

#include <gtest/gtest.h>

#include <type_traits>

#include <cmath>
#include <limits>

#include "frictopt/core/error.hpp"

namespace fo = frictopt::optim;

namespace {
// Projections are one QP solve on O(1) data: round-off level, with margin.
constexpr double kTol = 1e-10;
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

TEST(LinearConstraints, ConvertsFiniteBoundsAndInequalitiesToGeneralForm) {
  fo::LinearConstraints k;
  k.lower = Eigen::Vector2d(0.0, -kInf);
  k.upper = Eigen::Vector2d(1.0, 2.0);
  k.A_in = Eigen::MatrixXd{{1.0, 1.0}};
  k.b_in = Eigen::VectorXd::Ones(1);
  const fo::GeneralForm gf = fo::to_general_form(k, 2);
  ASSERT_EQ(gf.C.rows(), 4);  // lower[0], upper[0], upper[1], A_in[0]
  EXPECT_EQ(gf.row_origin[0], "lower[0]");
  EXPECT_EQ(gf.row_origin[3], "A_in[0]");
  const Eigen::Vector2d x(0.5, 0.25);
  EXPECT_LE((gf.C * x - gf.c).maxCoeff(), 0.0);
  EXPECT_EQ(k.max_violation(x), 0.0);
  // (−1, 3) violates lower[0], upper[1] and A_in[0], each by 1.
  EXPECT_DOUBLE_EQ(k.max_violation(Eigen::Vector2d(-1.0, 3.0)), 1.0);
}

TEST(LinearConstraints, ValidateNamesTheMismatchingBlock) {
  fo::LinearConstraints k;
  k.A_in = Eigen::MatrixXd::Ones(2, 3);
  k.b_in = Eigen::VectorXd::Ones(2);
  try {
    k.validate(2);
    FAIL() << "expected InvalidInput";
  } catch (const frictopt::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("A_in is 2x3"), std::string::npos) << e.what();
  }
  fo::LinearConstraints box;
  box.lower = Eigen::Vector2d(1.0, 0.0);
  box.upper = Eigen::Vector2d(0.0, 1.0);
  EXPECT_THROW(box.validate(2), frictopt::InvalidInput);  // empty box: lower[0] > upper[0]
}

TEST(ProjectOnto, ClampsToABox) {
  fo::LinearConstraints k;
  k.lower = Eigen::Vector3d(0, 0, 0);
  k.upper = Eigen::Vector3d(1, 1, 1);
  const fo::Projection p = fo::project_onto(k, Eigen::Vector3d(2.0, -1.0, 0.5));
  ASSERT_FALSE(p.feasible_set_empty);
  EXPECT_LE((p.point - Eigen::Vector3d(1.0, 0.0, 0.5)).norm(), kTol);
  EXPECT_NEAR(p.distance, std::sqrt(2.0), kTol);
}

TEST(ProjectOnto, ProjectsOntoAHyperplaneIntersectedWithAHalfSpace) {
  // {x1 + x2 + x3 = 1, x1 ≤ 0}: projecting (1,1,1) gives (0, 1/2, 1/2).
  fo::LinearConstraints k;
  k.A_eq = Eigen::MatrixXd::Ones(1, 3);
  k.b_eq = Eigen::VectorXd::Ones(1);
  k.A_in = Eigen::MatrixXd{{1.0, 0.0, 0.0}};
  k.b_in = Eigen::VectorXd::Zero(1);
  const fo::Projection p = fo::project_onto(k, Eigen::Vector3d(1, 1, 1));
  ASSERT_FALSE(p.feasible_set_empty);
  EXPECT_LE((p.point - Eigen::Vector3d(0.0, 0.5, 0.5)).norm(), kTol);
}

TEST(ProjectOnto, ReportsAnEmptyFeasibleSet) {
  fo::LinearConstraints k;
  k.lower = Eigen::Vector2d(0, 0);
  k.A_in = Eigen::MatrixXd{{1.0, 1.0}};
  k.b_in = Eigen::VectorXd::Constant(1, -1.0);  // x ≥ 0 and x1 + x2 ≤ −1
  const fo::Projection p = fo::project_onto(k, Eigen::Vector2d(0.3, 0.3));
  EXPECT_TRUE(p.feasible_set_empty);
  EXPECT_FALSE(p.message.empty());
}

TEST(LinearConstraints, IsTheOneCoreTypeAndNamesTheWorstViolation) {
  // optim::LinearConstraints and shape::LinearConstraints are the same core type: no copy
  // between them. describe_violation names the worst row by its name.
  static_assert(std::is_same_v<fo::LinearConstraints, frictopt::LinearConstraints>);
  frictopt::LinearConstraints k;
  k.variable_name = "alpha";
  k.lower = Eigen::Vector2d(0.0, 0.0);
  k.upper = Eigen::Vector2d(1.0, 1.0);
  k.A_in = Eigen::MatrixXd{{1.0, -1.0}};
  k.b_in = Eigen::VectorXd::Constant(1, 0.1);
  k.inequality_names = {"slope alpha0 - alpha1 <= 0.1"};
  k.A_eq = Eigen::MatrixXd{{1.0, 1.0}};
  k.b_eq = Eigen::VectorXd::Constant(1, 1.0);
  k.equality_names = {"volume: sum of alpha"};
  EXPECT_EQ(k.describe_violation(Eigen::Vector2d(0.5, 0.5), 1e-12), "");
  EXPECT_EQ(k.describe_violation(Eigen::Vector2d(-0.5, 1.5), 1e-12), "alpha[0] = -0.5; expected >= 0");
  EXPECT_EQ(k.describe_violation(Eigen::Vector2d(0.8, 0.2), 1e-12),
            "slope alpha0 - alpha1 <= 0.1: value 0.6; expected <= 0.1");
  EXPECT_EQ(k.describe_violation(Eigen::Vector2d(0.1, 0.1), 1e-12), "volume: sum of alpha = 0.2; expected 1");
  EXPECT_EQ(k.dimension(), 2);
}
