// SPDX-License-Identifier: MIT
// Minimizes the nonsmooth f(x) = |x₀ − 1| + 2|x₁ + ½| + ½·max(x₀, x₁) over the box [−2, 2]²
// with frictopt's bundle trust method, seeing f only through values and one subgradient per
// point. The unique minimizer is x* = (1, −½) with f* = ½: there ∂f = [−½, 3/2] × [−2, 2] ∋ 0
// (the max term's gradient (½, 0) lies inside the kinks of |·|), and away from x* some
// component of every subgradient is nonzero. Exit code 0 when it is found.
#include <cmath>
#include <cstdio>

#include "frictopt/optim/bundle_trust.hpp"
#include "frictopt/optim/linear_constraints.hpp"
#include "frictopt/optim/oracle.hpp"

int main() {
  using namespace frictopt;
  optim::FunctionOracle f([](const Eigen::Ref<const Eigen::VectorXd>& x) {
    const double a = x(0) - 1.0, b = x(1) + 0.5;
    Eigen::VectorXd g(2);
    g << (a >= 0 ? 1.0 : -1.0), (b >= 0 ? 2.0 : -2.0);
    if (x(0) >= x(1))  // one subgradient of max(x₀, x₁)
      g(0) += 0.5;
    else
      g(1) += 0.5;
    return optim::OracleResult::success(std::abs(a) + 2.0 * std::abs(b) + 0.5 * std::max(x(0), x(1)), g);
  });
  optim::LinearConstraints box;
  box.lower = Eigen::Vector2d(-2.0, -2.0);
  box.upper = Eigen::Vector2d(2.0, 2.0);
  const optim::BundleTrust method(optim::BundleTrust::Options{}, box);
  const optim::BundleTrust::Summary summary = method.minimize(f, Eigen::Vector2d(-1.5, 1.5));
  std::printf("%s\nx = (%.9f, %.9f), f = %.12f\n", summary.brief_report().c_str(), summary.x(0), summary.x(1),
              summary.f);
  const double error = (summary.x - Eigen::Vector2d(1.0, -0.5)).norm();
  return summary.converged() && error < 1e-6 && std::abs(summary.f - 0.5) < 1e-9 ? 0 : 1;
}
