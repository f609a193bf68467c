// SPDX-License-Identifier: MIT
// Reference Q1 element (bilinear quad / trilinear hex) in VTK node order, with tensor Gauss
// rules, and its boundary facet (segment / bilinear quad). Shared by mesh (volume, quality) and
// fem (kernels): what every element class provides (docs/architecture.md, "a new element").
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

#include "frictopt/mesh/element_kind.hpp"

namespace frictopt::mesh {

/// The boundary facet of a Q1 cell: a 2-node segment (2D) or a bilinear 4-node quadrilateral
/// (3D, cyclic order), with the 2^(Dim−1)-point Gauss rule, for surface loads.
template <int Dim>
struct Q1Facet {
  static constexpr int kNodes = Dim == 2 ? 2 : 4;
  static constexpr int kPoints = Dim == 2 ? 2 : 4;

  /// Facet shape functions and their ∂/∂(η1[, η2]) at Gauss point q, and its weight.
  static void shape(int q, Eigen::Matrix<double, kNodes, 1>& N, Eigen::Matrix<double, kNodes, Dim - 1>& dN,
                    double& weight) {
    const double g = 1.0 / std::sqrt(3.0);
    weight = 1.0;
    if constexpr (Dim == 2) {
      const double eta = q == 0 ? -g : g;
      N << 0.5 * (1 - eta), 0.5 * (1 + eta);
      dN << -0.5, 0.5;
    } else {
      const double e1 = (q == 0 || q == 3) ? -g : g, e2 = q < 2 ? -g : g;
      const double c[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (int a = 0; a < 4; ++a) {
        N(a) = 0.25 * (1 + c[a][0] * e1) * (1 + c[a][1] * e2);
        dN(a, 0) = 0.25 * c[a][0] * (1 + c[a][1] * e2);
        dN(a, 1) = 0.25 * c[a][1] * (1 + c[a][0] * e1);
      }
    }
  }
};

/// The Q1 cell: 4-node bilinear quadrilateral (Dim = 2) or 8-node trilinear hexahedron (Dim = 3).
template <int Dim>
struct Q1Element {
  static constexpr int kDim = Dim;
  static constexpr ElementKind kKind = Dim == 2 ? ElementKind::kQuad4 : ElementKind::kHex8;
  static constexpr int kNodes = Dim == 2 ? 4 : 8;
  using Facet = Q1Facet<Dim>;
  using Point = Eigen::Matrix<double, Dim, 1>;
  using Values = Eigen::Matrix<double, kNodes, 1>;
  using Gradients = Eigen::Matrix<double, kNodes, Dim>;  ///< row a = ∇_ξ N_a

  /// Reference corner coordinates in {−1, 1}^Dim, VTK order (counter-clockwise bottom, then top).
  static Eigen::Matrix<double, kNodes, Dim> corners() {
    Eigen::Matrix<double, kNodes, Dim> c;
    const double q[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int a = 0; a < kNodes; ++a) {
      c(a, 0) = q[a % 4][0];
      c(a, 1) = q[a % 4][1];
      if constexpr (Dim == 3) c(a, 2) = a < 4 ? -1.0 : 1.0;
    }
    return c;
  }

  static Values values(const Point& xi) {
    static const auto c = corners();
    Values N;
    for (int a = 0; a < kNodes; ++a) {
      double v = 1.0;
      for (int i = 0; i < Dim; ++i) v *= 0.5 * (1.0 + c(a, i) * xi(i));
      N(a) = v;
    }
    return N;
  }

  static Gradients gradients(const Point& xi) {
    static const auto c = corners();
    Gradients G;
    for (int a = 0; a < kNodes; ++a)
      for (int j = 0; j < Dim; ++j) {
        double v = 0.5 * c(a, j);
        for (int i = 0; i < Dim; ++i)
          if (i != j) v *= 0.5 * (1.0 + c(a, i) * xi(i));
        G(a, j) = v;
      }
    return G;
  }

  /// The reference cell's centre (where the constant-strain part of a field is sampled).
  static Point centre() { return Point::Zero(); }

  /// det of the Jacobian at corner a with its columns (the edge directions there) normalized:
  /// 1 for a box, 0 degenerate, < 0 inverted (the Verdict library's hex/quad scaled Jacobian).
  static double scaled_jacobian_at_corner(const Eigen::Matrix<double, kNodes, Dim>& Xe, int a) {
    static const auto c = corners();
    Eigen::Matrix<double, Dim, Dim> J = Xe.transpose() * gradients(c.row(a).transpose());
    const Eigen::Matrix<double, 1, Dim> lengths = J.colwise().norm();
    if (!(lengths.minCoeff() > 0)) return 0.0;  // a collapsed edge
    for (int k = 0; k < Dim; ++k) J.col(k) /= lengths(k);
    return J.determinant();
  }

  /// Tensor Gauss–Legendre rule with 2 points per direction (exact for the Q1 stiffness on
  /// parallelepipeds; the standard full integration for Q1 elasticity).
  static std::array<std::pair<Point, double>, kNodes> quadrature() {
    std::array<std::pair<Point, double>, kNodes> rule;
    const double g = 1.0 / std::sqrt(3.0);
    const auto c = corners();
    for (int a = 0; a < kNodes; ++a) rule[a] = {Point(c.row(a).transpose() * g), 1.0};
    return rule;
  }
};

}  // namespace frictopt::mesh
