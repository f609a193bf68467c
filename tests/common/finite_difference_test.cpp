// SPDX-License-Identifier: MIT
// The checker must accept a right derivative and reject a deliberately wrong one.
#include "common/finite_difference.hpp"

#include <gtest/gtest.h>

namespace frictopt::testing {
namespace {

double rosenbrock(const Eigen::VectorXd& x) {
  return 100 * std::pow(x(1) - x(0) * x(0), 2) + std::pow(1 - x(0), 2);
}
Eigen::VectorXd rosenbrock_gradient(const Eigen::VectorXd& x) {
  Eigen::VectorXd g(2);
  g(0) = -400 * x(0) * (x(1) - x(0) * x(0)) - 2 * (1 - x(0));
  g(1) = 200 * (x(1) - x(0) * x(0));
  return g;
}

TEST(FiniteDifferenceChecker, AcceptsCorrectGradient) {
  Eigen::VectorXd x(2);
  x << -1.2, 1.0;
  const Eigen::VectorXd fd = central_gradient(rosenbrock, x, central_step(x));
  EXPECT_LE((fd - rosenbrock_gradient(x)).norm(), 1e-7 * rosenbrock_gradient(x).norm());
  std::mt19937_64 rng{kSeed};
  const auto ratios = taylor_ratios(rosenbrock, x, rosenbrock_gradient(x), random_direction(rng, 2), 1e-2);
  EXPECT_NEAR(ratios.front(), 4.0, 0.5);
}

TEST(FiniteDifferenceChecker, RejectsWrongGradient) {
  Eigen::VectorXd x(2);
  x << -1.2, 1.0;
  Eigen::VectorXd wrong = rosenbrock_gradient(x);
  wrong(1) *= 1.001;  // a 0.1% error in one component
  const Eigen::VectorXd fd = central_gradient(rosenbrock, x, central_step(x));
  EXPECT_GT((fd - wrong).norm(), 1e-5 * wrong.norm());
  std::mt19937_64 rng{kSeed};
  const auto ratios = taylor_ratios(rosenbrock, x, wrong, random_direction(rng, 2), 1e-6);
  EXPECT_LT(ratios.back(), 2.5);  // first-order error: ratio -> 2, not 4
}

}  // namespace
}  // namespace frictopt::testing
