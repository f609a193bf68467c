// SPDX-License-Identifier: MIT
// The friction coefficients of a law as controls (thesis §4 remark that other
// controls than the shape fit the same adjoint): their names, values, and the derivatives of
// the friction set's vertices (polygonal laws) or semi-axes and orientation (disc, ellipse).
// The orientation φ of a turned law (FrictionLaw::rotated) is a parameter only when asked for
// (docs/theory/friction-design.md: the law's orientation as a design variable).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "frictopt/contact/friction_law.hpp"

namespace frictopt::sensitivity {

struct FrictionParameters {
  std::vector<std::string> names;  ///< e.g. "mu", "mu_vertices[2]", "mu_x", "mu_minus", "orientation"
  Eigen::VectorXd values;
  /// Polygonal laws: vertex_derivatives[k][j] = ∂w_j/∂p_k (for the orientation: J w_j, J the
  /// quarter turn, since w_j(φ) = R(φ) w_j(0) and R' = J R).
  std::vector<std::vector<Eigen::Vector2d>> vertex_derivatives;
  /// Smooth laws (disc, ellipse): semi_axis_derivatives[k] = ∂c/∂p_k, c the law's own
  /// coefficients (FrictionLaw::coefficients(): disc μ, ellipse (μ_x, μ_y)); the exposed point
  /// moves by FrictionLaw::exposed_point_coefficient_jacobian(u)·∂c/∂p_k.
  std::vector<Eigen::VectorXd> semi_axis_derivatives;
  /// Smooth laws: orientation_derivatives[k] = ∂φ/∂p_k (1 for the orientation, 0 otherwise); the
  /// exposed point then moves by ∂w/∂φ = J w(u) − (∂w/∂u) J u
  /// (FrictionLaw::exposed_point_orientation_derivative).
  std::vector<double> orientation_derivatives;
};

/// Which parameters friction_parameters() lists.
struct FrictionParameterOptions {
  /// Append the orientation φ [rad] (FrictionLaw::orientation) as the last parameter, named
  /// "orientation". 3D laws only: InvalidInput for a 2D interval law.
  bool orientation = false;
};

/// The law's own coefficients (FrictionLaw::coefficient_names: interval (μ₋, μ₊); disc μ;
/// regular_polygon μ; polygon μ_j (w_j = μ_j R(φ) v_j); ellipse and ellipse_polygon (μ_x, μ_y)),
/// then φ if asked for.
FrictionParameters friction_parameters(const contact::FrictionLaw& law, FrictionParameterOptions options = {});

/// The orientation φ alone (one parameter, "orientation"), e.g. for a design variable that turns
/// the law; InvalidInput for a 2D interval law.
FrictionParameters orientation_parameter(const contact::FrictionLaw& law);

}  // namespace frictopt::sensitivity
