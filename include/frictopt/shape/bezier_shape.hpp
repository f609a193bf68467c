// SPDX-License-Identifier: MIT
// The Bézier bottom of the body: a curve on [0, a] (2D) or a tensor-product surface on
// [0, a] × [0, b] (3D), linear in its control heights α (docs/theory/problem.md §2).
#pragma once

#include <Eigen/Core>
#include <array>

namespace frictopt::shape {

/// The contact surface x_dim = G_α(x') with x' = x1 (2D) or (x1, x2) (3D):
///   2D: G_α(x1)     = Σ_i α_i b_i(x1/a),                 i = 0..m1−1  (thesis §5.2)
///   3D: G_α(x1, x2) = Σ_{i,j} α_{ij} b_i(x1/a) b_j(x2/b),  i < m1, j < m2 (thesis §6.1)
/// with Bernstein polynomials b of degree m−1. The design vector α has d = m1 (2D) or
/// d = m1·m2 (3D) entries, ordered row-major with x1 fastest: k = i + m1·j
/// (docs/theory/problem.md §2; any fixed order is equivalent).
/// Only the heights are design variables; control abscissae are equispaced.
class BezierShape {
 public:
  /// 2D curve with m1 >= 2 control points on [0, a]. Throws InvalidInput on bad sizes.
  static BezierShape curve(double a, int m1);
  /// 3D surface with an m1 × m2 control net (each >= 2) on [0, a] × [0, b].
  static BezierShape surface(double a, double b, int m1, int m2);

  int dim() const { return dim_; }
  /// Number of design variables d.
  int num_controls() const { return dim_ == 2 ? m_[0] : m_[0] * m_[1]; }
  /// Control points per direction (m1, m2); m2 = 1 in 2D.
  std::array<int, 2> control_net() const { return m_; }
  /// Extents (a, b) of the parameter domain; b = 1 in 2D (unit thickness).
  std::array<double, 2> extents() const { return extent_; }
  /// Area of the parameter domain: a (2D, per unit thickness) or a·b (3D).
  double base_measure() const { return extent_[0] * extent_[1]; }

  /// Row of the gap map at the in-plane point x' (size dim−1): G_α(x') = basis(x')·α.
  Eigen::VectorXd basis(const Eigen::Ref<const Eigen::VectorXd>& x_plane) const;
  /// ∂basis/∂x'_c for c < dim−1 (the surface slope per unit α).
  Eigen::VectorXd basis_derivative(const Eigen::Ref<const Eigen::VectorXd>& x_plane, int c) const;
  /// G_α(x').
  double height(const Eigen::Ref<const Eigen::VectorXd>& alpha,
                const Eigen::Ref<const Eigen::VectorXd>& x_plane) const;
  /// The constant gap matrix B̃ (rows = points, one per row of `points_plane`, which is
  /// n × (dim−1)): g = B̃ α are the initial gaps at those points (docs/theory/problem.md §3).
  Eigen::MatrixXd gap_matrix(const Eigen::Ref<const Eigen::MatrixXd>& points_plane) const;
  /// Weights w with ∫ G_α dx' = wᵀα; every entry equals base_measure()/d because each
  /// Bernstein polynomial integrates to 1/(degree+1) (docs/theory/problem.md §2).
  Eigen::VectorXd integral_weights() const;

 private:
  BezierShape(int dim, std::array<double, 2> extent, std::array<int, 2> m);
  int dim_;
  std::array<double, 2> extent_;
  std::array<int, 2> m_;
};

}  // namespace frictopt::shape
