// SPDX-License-Identifier: MIT
#include "frictopt/shape/bezier_shape.hpp"

#include <cmath>
#include <string>

#include "frictopt/core/error.hpp"
#include "frictopt/core/validation.hpp"
#include "frictopt/shape/bernstein.hpp"

namespace frictopt::shape {
namespace {

}  // namespace

BezierShape::BezierShape(int dim, std::array<double, 2> extent, std::array<int, 2> m)
    : dim_(dim), extent_(extent), m_(m) {}

BezierShape BezierShape::curve(double a, int m1) {
  require_field(a > 0 && std::isfinite(a), "BezierShape", "a", a, "a finite value > 0");
  require_field(m1 >= 2, "BezierShape", "control points", m1, ">= 2");
  return BezierShape(2, {a, 1.0}, {m1, 1});
}

BezierShape BezierShape::surface(double a, double b, int m1, int m2) {
  require_field(a > 0 && std::isfinite(a), "BezierShape", "a", a, "a finite value > 0");
  require_field(b > 0 && std::isfinite(b), "BezierShape", "b", b, "a finite value > 0");
  if (m1 < 2 || m2 < 2) {
    fail_field("BezierShape", "control net", std::to_string(m1) + " x " + std::to_string(m2), "at least 2 x 2");
  }
  return BezierShape(3, {a, b}, {m1, m2});
}

Eigen::VectorXd BezierShape::basis(const Eigen::Ref<const Eigen::VectorXd>& x_plane) const {
  FRICTOPT_ASSERT(x_plane.size() == dim_ - 1, "point dimension");
  const Eigen::VectorXd b1 = bernstein_basis(m_[0] - 1, x_plane(0) / extent_[0]);
  if (dim_ == 2) return b1;
  const Eigen::VectorXd b2 = bernstein_basis(m_[1] - 1, x_plane(1) / extent_[1]);
  Eigen::VectorXd row(num_controls());
  for (int j = 0; j < m_[1]; ++j)
    for (int i = 0; i < m_[0]; ++i) row(i + m_[0] * j) = b1(i) * b2(j);
  return row;
}

Eigen::VectorXd BezierShape::basis_derivative(const Eigen::Ref<const Eigen::VectorXd>& x_plane,
                                              int c) const {
  FRICTOPT_ASSERT(c >= 0 && c < dim_ - 1, "derivative direction");
  const double t1 = x_plane(0) / extent_[0];
  Eigen::VectorXd b1 = c == 0 ? Eigen::VectorXd(bernstein_basis_derivative(m_[0] - 1, t1) / extent_[0])
                              : bernstein_basis(m_[0] - 1, t1);
  if (dim_ == 2) return b1;
  const double t2 = x_plane(1) / extent_[1];
  Eigen::VectorXd b2 = c == 1 ? Eigen::VectorXd(bernstein_basis_derivative(m_[1] - 1, t2) / extent_[1])
                              : bernstein_basis(m_[1] - 1, t2);
  Eigen::VectorXd row(num_controls());
  for (int j = 0; j < m_[1]; ++j)
    for (int i = 0; i < m_[0]; ++i) row(i + m_[0] * j) = b1(i) * b2(j);
  return row;
}

double BezierShape::height(const Eigen::Ref<const Eigen::VectorXd>& alpha,
                           const Eigen::Ref<const Eigen::VectorXd>& x_plane) const {
  FRICTOPT_ASSERT(alpha.size() == num_controls(), "design size");
  return basis(x_plane).dot(alpha);
}

Eigen::MatrixXd BezierShape::gap_matrix(const Eigen::Ref<const Eigen::MatrixXd>& points_plane) const {
  FRICTOPT_ASSERT(points_plane.cols() == dim_ - 1, "point dimension");
  Eigen::MatrixXd B(points_plane.rows(), num_controls());
  for (Eigen::Index r = 0; r < points_plane.rows(); ++r)
    B.row(r) = basis(points_plane.row(r).transpose()).transpose();
  return B;
}

Eigen::VectorXd BezierShape::integral_weights() const {
  return Eigen::VectorXd::Constant(num_controls(), base_measure() / num_controls());
}

}  // namespace frictopt::shape
