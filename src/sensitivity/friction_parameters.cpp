// SPDX-License-Identifier: MIT
#include "frictopt/sensitivity/friction_parameters.hpp"

#include <fmt/format.h>

#include "friction_geometry.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::sensitivity {
namespace {
void require_orientable(const contact::FrictionLaw& law) {
  if (law.dim() == 2)
    throw InvalidInput(fmt::format("{}: a 2D interval law has no orientation parameter (its tangent space is a line)",
                                   law.describe()));
}

// Appends φ: polygon vertices move by J w_j, smooth sets carry ∂φ/∂p = 1.
void append_orientation(const contact::FrictionLaw& law, FrictionParameters& out) {
  require_orientable(law);
  const Eigen::Index k = out.values.size();
  out.names.push_back("orientation");
  out.values.conservativeResize(k + 1);
  out.values(k) = law.orientation();
  for (double& d : out.orientation_derivatives) d = 0.0;
  if (law.is_polygonal()) {
    std::vector<Eigen::Vector2d> d;
    for (const Eigen::Vector2d& w : law.vertices()) d.push_back(detail::quarter_turn(w));
    out.vertex_derivatives.push_back(std::move(d));
  } else {
    out.semi_axis_derivatives.emplace_back(Eigen::VectorXd::Zero(law.coefficients().size()));
    out.orientation_derivatives.push_back(1.0);
  }
}
}  // namespace

FrictionParameters friction_parameters(const contact::FrictionLaw& law, FrictionParameterOptions options) {
  FrictionParameters out;
  out.names = law.coefficient_names();
  out.values = law.coefficients();
  if (law.is_polygonal()) {
    out.vertex_derivatives = law.vertex_coefficient_derivatives();
  } else {
    // The parameters are the law's coefficients: ∂c/∂p_k = e_k.
    const Eigen::Index nc = out.values.size();
    for (Eigen::Index k = 0; k < nc; ++k) {
      out.semi_axis_derivatives.emplace_back(Eigen::VectorXd::Unit(nc, k));
      out.orientation_derivatives.push_back(0.0);
    }
  }
  if (options.orientation) append_orientation(law, out);
  return out;
}

FrictionParameters orientation_parameter(const contact::FrictionLaw& law) {
  FrictionParameters out;
  append_orientation(law, out);
  return out;
}

}  // namespace frictopt::sensitivity
