// SPDX-License-Identifier: MIT
#include "projection_jacobian.hpp"

namespace frictopt::petsc {

ProjectionLinearization linearize_projection(const contact::FrictionLaw& law, const Eigen::Vector2d& x, double s) {
  ProjectionLinearization out;
  if (!(s > 0.0) || law.is_zero()) return out;
  Eigen::Vector2d y = x / s;
  if (law.dim() == 2) y.y() = 0.0;
  const contact::FrictionLaw::ProjectionJacobian p = law.projection_jacobian(y);
  out.value = s * p.point;
  out.d_x = p.jacobian;
  out.d_s = p.point - p.jacobian * y;
  out.face = p.face;
  return out;
}

}  // namespace frictopt::petsc
