// SPDX-License-Identifier: MIT
// Reference Q1 element (bilinear quad / trilinear hex) in VTK node order, with tensor Gauss
// rules. Shared by mesh (volume, quality) and fem (kernels).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

namespace frictopt::mesh {

template <int Dim>
struct Q1Element {
  static constexpr int kNodes = Dim == 2 ? 4 : 8;
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

  /// Tensor Gauss–Legendre rule with 2 points per direction (exact for the Q1 stiffness on
  /// parallelepipeds; the standard full integration for Q1 elasticity).
  static std::array<std::pair<Point, double>, kNodes> gauss2() {
    std::array<std::pair<Point, double>, kNodes> rule;
    const double g = 1.0 / std::sqrt(3.0);
    const auto c = corners();
    for (int a = 0; a < kNodes; ++a) rule[a] = {Point(c.row(a).transpose() * g), 1.0};
    return rule;
  }
};

}  // namespace frictopt::mesh
