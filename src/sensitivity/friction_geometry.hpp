// SPDX-License-Identifier: MIT
// Plane-vector helpers shared by the adjoint and the parameter sensitivities (private to the
// sensitivity module). The friction sets' own geometry and derivatives (exposed point and its
// Jacobians) are members of contact::FrictionLaw.
#pragma once

#include <Eigen/Core>

namespace frictopt::sensitivity::detail {

/// a × b for plane vectors.
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a(0) * b(1) - a(1) * b(0); }

/// J v: v turned by +90° (J = R(π/2), the derivative of R(φ) is J R(φ)).
inline Eigen::Vector2d quarter_turn(const Eigen::Vector2d& v) { return {-v(1), v(0)}; }

}  // namespace frictopt::sensitivity::detail
