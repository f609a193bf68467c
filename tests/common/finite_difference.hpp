// SPDX-License-Identifier: MIT
// The shared derivative checker: central differences with
// h = cbrt(eps)·max(1, |x|) along seeded random directions, plus a Taylor test whose observed
// error ratios tell a bug (ratio ~ 2 for a first-order error) from round-off.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace frictopt::testing {

inline constexpr std::uint64_t kSeed = 20261121;

/// "[a, b, c]" for the printed comparisons of the derivative tests.
inline std::string format_vector(const Eigen::VectorXd& v) {
  std::string out = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? ", " : "") + std::to_string(v(i));
  return out + "]";
}

/// Central-difference step for a point x: cbrt(eps)·max(1, ‖x‖∞).
inline double central_step(const Eigen::VectorXd& x) {
  return std::cbrt(std::numeric_limits<double>::epsilon()) *
         std::max(1.0, x.size() ? x.cwiseAbs().maxCoeff() : 0.0);
}

/// Central difference of a scalar function f along direction v at x.
inline double central_directional(const std::function<double(const Eigen::VectorXd&)>& f,
                                  const Eigen::VectorXd& x, const Eigen::VectorXd& v, double h) {
  return (f(x + h * v) - f(x - h * v)) / (2.0 * h);
}

/// Full central-difference gradient of f at x (small problems only).
inline Eigen::VectorXd central_gradient(const std::function<double(const Eigen::VectorXd&)>& f,
                                        const Eigen::VectorXd& x, double h) {
  Eigen::VectorXd g(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(x.size());
    e(i) = 1.0;
    g(i) = central_directional(f, x, e, h);
  }
  return g;
}

/// Full central-difference Jacobian of a vector map F at x (columns = ∂F/∂x_i).
inline Eigen::MatrixXd central_jacobian(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& F, const Eigen::VectorXd& x,
    double h) {
  Eigen::MatrixXd J;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(x.size());
    e(i) = h;
    Eigen::VectorXd col = (F(x + e) - F(x - e)) / (2.0 * h);
    if (i == 0) J.resize(col.size(), x.size());
    J.col(i) = col;
  }
  return J;
}

/// Seeded random unit direction of dimension n.
inline Eigen::VectorXd random_direction(std::mt19937_64& rng, Eigen::Index n) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v(i) = normal(rng);
  return v / v.norm();
}

/// Taylor test: errors e(h) = |f(x+hv) − f(x) − h·g·v| for h = h0, h0/2, h0/4, ...
/// Returns the ratios e(h)/e(h/2); a correct gradient gives ~4 (second order) until round-off.
inline std::vector<double> taylor_ratios(const std::function<double(const Eigen::VectorXd&)>& f,
                                         const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                                         const Eigen::VectorXd& v, double h0, int levels = 4) {
  const double f0 = f(x);
  const double slope = g.dot(v);
  std::vector<double> errors;
  double h = h0;
  for (int k = 0; k <= levels; ++k, h /= 2) errors.push_back(std::abs(f(x + h * v) - f0 - h * slope));
  std::vector<double> ratios;
  for (std::size_t k = 0; k + 1 < errors.size(); ++k)
    ratios.push_back(errors[k] / std::max(errors[k + 1], std::numeric_limits<double>::min()));
  return ratios;
}

/// |a − b| ≤ rtol·max(|a|, |b|) + atol.
inline bool close(double a, double b, double rtol, double atol = 0.0) {
  return std::abs(a - b) <= rtol * std::max(std::abs(a), std::abs(b)) + atol;
}

}  // namespace frictopt::testing
