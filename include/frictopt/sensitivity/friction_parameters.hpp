// SPDX-License-Identifier: MIT
// The friction coefficients of a law as controls (issue 4 item 4, thesis §4 remark that other
// controls than the shape fit the same adjoint): their names, values, and the derivatives of
// the friction set's vertices (polygonal laws) or semi-axes (disc, ellipse).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "frictopt/contact/friction_law.hpp"

namespace frictopt::sensitivity {

struct FrictionParameters {
  std::vector<std::string> names;  ///< e.g. "mu", "mu_vertices[2]", "mu_x", "mu_minus"
  Eigen::VectorXd values;
  /// Polygonal laws: vertex_derivatives[k][j] = ∂w_j/∂p_k.
  std::vector<std::vector<Eigen::Vector2d>> vertex_derivatives;
  /// Disc/ellipse: semi_axis_derivatives[k] = ∂(μ_x, μ_y)/∂p_k.
  std::vector<Eigen::Vector2d> semi_axis_derivatives;
};

/// Parameters per law kind: interval (μ₋, μ₊); disc μ; regular_polygon μ; polygon μ_j
/// (w_j = μ_j v_j); ellipse and ellipse_polygon (μ_x, μ_y).
FrictionParameters friction_parameters(const contact::FrictionLaw& law);

}  // namespace frictopt::sensitivity
