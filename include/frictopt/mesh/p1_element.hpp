// SPDX-License-Identifier: MIT
// Reference P1 element (linear triangle / linear tetrahedron) in VTK node order, with its
// quadrature, and its boundary facet (segment / linear triangle). The same interface as
// Q1Element (q1_element.hpp), so every kernel templated over an element class serves it
// (docs/architecture.md, "A new element").
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <utility>

#include "frictopt/mesh/element_kind.hpp"
#include "frictopt/mesh/q1_element.hpp"

namespace frictopt::mesh {

/// The boundary facet of a P1 cell: the 2-node segment (2D; the same as Q1's, so its two-point
/// rule) or the linear 3-node triangle (3D) on the reference triangle {η >= 0, η1 + η2 <= 1}
/// with the one-point centroid rule: exact for what the facet kernels integrate with a linear
/// facet (∫ N_a t dS and its coordinate derivatives: degree 1 times a constant area density).
template <int Dim>
struct P1Facet;

template <>
struct P1Facet<2> : Q1Facet<2> {};

template <>
struct P1Facet<3> {
  static constexpr int kNodes = 3;
  static constexpr int kPoints = 1;

  static void shape(int /*q*/, Eigen::Matrix<double, 3, 1>& N, Eigen::Matrix<double, 3, 2>& dN, double& weight) {
    N.setConstant(1.0 / 3.0);
    dN << -1, -1, 1, 0, 0, 1;
    weight = 0.5;  // the reference triangle's area
  }
};

/// The P1 cell: 3-node linear triangle (Dim = 2) or 4-node linear tetrahedron (Dim = 3), shape
/// functions N_0 = 1 − Σξ, N_a = ξ_a on the reference simplex {ξ >= 0, Σξ <= 1}. The strain is
/// constant in the cell, so the one-point rule integrates the stiffness, its shape derivative
/// and the volume exactly.
template <int Dim>
struct P1Element {
  static constexpr int kDim = Dim;
  static constexpr ElementKind kKind = Dim == 2 ? ElementKind::kTri3 : ElementKind::kTet4;
  static constexpr int kNodes = Dim + 1;
  using Facet = P1Facet<Dim>;
  using Point = Eigen::Matrix<double, Dim, 1>;
  using Values = Eigen::Matrix<double, kNodes, 1>;
  using Gradients = Eigen::Matrix<double, kNodes, Dim>;  ///< row a = ∇_ξ N_a

  /// Reference vertices: the origin, then the unit points e_1 .. e_Dim (VTK order).
  static Eigen::Matrix<double, kNodes, Dim> corners() {
    Eigen::Matrix<double, kNodes, Dim> c = Eigen::Matrix<double, kNodes, Dim>::Zero();
    for (int a = 1; a < kNodes; ++a) c(a, a - 1) = 1.0;
    return c;
  }

  static Values values(const Point& xi) {
    Values N;
    N(0) = 1.0 - xi.sum();
    N.template tail<Dim>() = xi;
    return N;
  }

  static Gradients gradients(const Point& /*xi*/) {
    Gradients G;
    G.row(0).setConstant(-1.0);
    G.template bottomRows<Dim>().setIdentity();
    return G;
  }

  /// The centroid.
  static Point centre() { return Point::Constant(1.0 / kNodes); }

  /// The scaled Jacobian at vertex a: det of the unit edge vectors leaving it (ordered so that a
  /// positively oriented cell gives det > 0), times √2 (3D) or 2/√3 (2D) so that the equilateral
  /// simplex scores 1 — the Verdict library's tetrahedron and triangle measure. A right-angled
  /// corner of a structured split scores √2 (3D) or 2/√3, as in Verdict; 0 degenerate, < 0 inverted.
  static double scaled_jacobian_at_corner(const Eigen::Matrix<double, kNodes, Dim>& Xe, int a) {
    // The other vertices in an order of the same orientation as (1, 2, 3) seen from vertex 0.
    static constexpr int kOthers3[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    static constexpr int kOthers2[3][2] = {{1, 2}, {2, 0}, {0, 1}};
    Eigen::Matrix<double, Dim, Dim> E;
    for (int k = 0; k < Dim; ++k) {
      const int b = Dim == 3 ? kOthers3[a][k] : kOthers2[a][k];
      E.col(k) = (Xe.row(b) - Xe.row(a)).transpose();
      const double length = E.col(k).norm();
      if (!(length > 0)) return 0.0;  // a collapsed edge
      E.col(k) /= length;
    }
    return E.determinant() * (Dim == 3 ? std::sqrt(2.0) : 2.0 / std::sqrt(3.0));
  }

  /// One point at the centroid with the reference simplex's volume (1/2, 1/6).
  static std::array<std::pair<Point, double>, 1> quadrature() {
    return {std::pair<Point, double>{centre(), Dim == 2 ? 0.5 : 1.0 / 6.0}};
  }
};

}  // namespace frictopt::mesh
