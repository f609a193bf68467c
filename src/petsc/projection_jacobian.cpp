// SPDX-License-Identifier: MIT
#include "projection_jacobian.hpp"

#include <cmath>

namespace frictopt::petsc {
namespace {

// J_W(y) for a polygon (or the 2D interval) at y outside W, from the face its projection
// lies on. The face tolerance is relative to the set's size: the projection is exact to
// rounding, so 1e-12·max|w| separates an edge point from a vertex robustly.
Eigen::Matrix2d polygon_jacobian(const contact::FrictionLaw& law, const Eigen::Vector2d& p, contact::FaceLocation& face) {
  face = law.locate(p, 1.0, 1e-12 * law.max_coefficient());
  if (face.face != contact::FrictionFace::kEdge) return Eigen::Matrix2d::Zero();  // vertex: P constant
  const Eigen::Vector2d e = law.edge_normals()[static_cast<std::size_t>(face.index)];
  const Eigen::Vector2d t(-e.y(), e.x());
  return t * t.transpose();
}

// In the law's own frame (a turned law: R J₀(Rᵀy, Rᵀp) Rᵀ, FrictionLaw::frame).
Eigen::Matrix2d ellipse_jacobian(const contact::FrictionLaw& law, const Eigen::Vector2d& y_plane, const Eigen::Vector2d& p_plane) {
  const Eigen::Matrix2d& R = law.frame();
  const Eigen::Vector2d y = R.transpose() * y_plane, p = R.transpose() * p_plane;
  const Eigen::Vector2d axes = law.semi_axes();
  const Eigen::Vector2d D(1.0 / (axes.x() * axes.x()), 1.0 / (axes.y() * axes.y()));
  const Eigen::Vector2d Dp = D.cwiseProduct(p);
  // y − p = γ D p: the multiplier in the least-squares sense (exact up to the projection's
  // rounding).
  const double gamma = std::max(0.0, (y - p).dot(Dp) / Dp.squaredNorm());
  const Eigen::Vector2d M = (Eigen::Vector2d::Ones() + gamma * D).cwiseInverse();
  const Eigen::Vector2d MDp = M.cwiseProduct(Dp);
  return R * (Eigen::Matrix2d(M.asDiagonal()) - MDp * MDp.transpose() / Dp.dot(MDp)) * R.transpose();
}

}  // namespace

ProjectionLinearization linearize_projection(const contact::FrictionLaw& law, const Eigen::Vector2d& x, double s) {
  ProjectionLinearization out;
  if (!(s > 0.0) || law.is_zero()) return out;
  Eigen::Vector2d y = x / s;
  if (law.dim() == 2) y.y() = 0.0;
  const Eigen::Vector2d p = law.project(y, 1.0);
  Eigen::Matrix2d J;
  if (law.boundary_offset(y, 1.0) <= 0.0) {
    J.setIdentity();
    out.face = {contact::FrictionFace::kInterior, -1};
  } else if (law.is_polygonal()) {
    J = polygon_jacobian(law, p, out.face);
  } else {
    J = ellipse_jacobian(law, y, p);
    out.face = {contact::FrictionFace::kSmooth, -1};
  }
  if (law.dim() == 2) {  // one tangential component
    J(0, 1) = J(1, 0) = J(1, 1) = 0.0;
  }
  out.value = s * p;
  out.d_x = J;
  out.d_s = p - J * y;
  return out;
}

}  // namespace frictopt::petsc
