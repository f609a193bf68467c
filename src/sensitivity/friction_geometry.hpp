// SPDX-License-Identifier: MIT
// Small geometric helpers of the friction sets shared by the adjoint and the parameter
// sensitivities (private to the sensitivity module).
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "frictopt/contact/friction_law.hpp"

namespace frictopt::sensitivity::detail {

/// a × b for plane vectors.
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a(0) * b(1) - a(1) * b(0); }

/// ∂w/∂d of the exposed point w(d) = A d/√(dᵀAd), A = diag(a², b²), of a disc/ellipse with
/// semi-axes (a, b): A/s − (Ad)(Ad)ᵀ/s³, s = √(dᵀAd).
inline Eigen::Matrix2d exposed_point_jacobian(const Eigen::Vector2d& semi_axes, const Eigen::Vector2d& d) {
  const Eigen::Matrix2d A = semi_axes.cwiseProduct(semi_axes).asDiagonal();
  const Eigen::Vector2d Ad = A * d;
  const double s = std::sqrt(d.dot(Ad));
  return A / s - Ad * Ad.transpose() / (s * s * s);
}

/// ∂w/∂(a, b) of the same exposed point (columns ∂/∂a, ∂/∂b).
inline Eigen::Matrix2d exposed_point_axis_jacobian(const Eigen::Vector2d& semi_axes, const Eigen::Vector2d& d) {
  const double a = semi_axes(0), b = semi_axes(1);
  const double s = std::sqrt(a * a * d(0) * d(0) + b * b * d(1) * d(1));
  const double ds_da = a * d(0) * d(0) / s, ds_db = b * d(1) * d(1) / s;
  Eigen::Matrix2d J;
  J(0, 0) = 2 * a * d(0) / s - a * a * d(0) * ds_da / (s * s);
  J(1, 0) = -b * b * d(1) * ds_da / (s * s);
  J(0, 1) = -a * a * d(0) * ds_db / (s * s);
  J(1, 1) = 2 * b * d(1) / s - b * b * d(1) * ds_db / (s * s);
  return J;
}

/// J v: v turned by +90° (J = R(π/2), the derivative of R(φ) is J R(φ)).
inline Eigen::Vector2d quarter_turn(const Eigen::Vector2d& v) { return {-v(1), v(0)}; }

/// ∂w/∂u of the exposed point of a (possibly turned) disc/ellipse law: w(u) = R w₀(Rᵀu) with w₀
/// the exposed point of the unturned set, so ∂w/∂u = R (∂w₀/∂d)(Rᵀu) Rᵀ.
inline Eigen::Matrix2d exposed_point_jacobian(const contact::FrictionLaw& law, const Eigen::Vector2d& u) {
  const Eigen::Matrix2d& R = law.frame();
  return R * exposed_point_jacobian(law.semi_axes(), R.transpose() * u) * R.transpose();
}

/// ∂w/∂(μ_x, μ_y) of the same exposed point: R (∂w₀/∂(a, b))(Rᵀu).
inline Eigen::Matrix2d exposed_point_axis_jacobian(const contact::FrictionLaw& law, const Eigen::Vector2d& u) {
  return law.frame() * exposed_point_axis_jacobian(law.semi_axes(), law.frame().transpose() * u);
}

/// ∂w/∂φ of the same exposed point at fixed u. With R'(φ) = J R and (Rᵀ)' = −Rᵀ J:
///   ∂/∂φ [R w₀(Rᵀu)] = J w(u) − (∂w/∂u)(u) J u.
/// For a disc this is 0 (w = μ u/|u| commutes with every rotation).
inline Eigen::Vector2d exposed_point_orientation_derivative(const contact::FrictionLaw& law, const Eigen::Vector2d& u) {
  return quarter_turn(law.exposed_point(u)) - exposed_point_jacobian(law, u) * quarter_turn(u);
}

}  // namespace frictopt::sensitivity::detail
