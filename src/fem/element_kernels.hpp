// SPDX-License-Identifier: MIT
// Element-level kernels of isoparametric linear elasticity (private to fem), templates over the
// element class (mesh::Q1Element<2>, mesh::Q1Element<3>, ...): stiffness, stresses, the
// derivative of pᵀK_e(X)u with respect to the element's node coordinates, and surface loads on
// the element's facets. A new element needs no change here, only its class (mesh/elements.hpp).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "frictopt/mesh/elements.hpp"

namespace frictopt::fem::detail {

template <class ElementType>
struct ElasticityKernel {
  using Element = ElementType;
  static constexpr int Dim = Element::kDim;
  static constexpr int kNodes = Element::kNodes;
  static constexpr int kDofs = kNodes * Dim;
  using Coordinates = Eigen::Matrix<double, kNodes, Dim>;  ///< row a = node a
  using Matrix = Eigen::Matrix<double, kDofs, kDofs>;
  using Vector = Eigen::Matrix<double, kDofs, 1>;
  using Tensor = Eigen::Matrix<double, Dim, Dim>;

  double lambda;  // Lamé λ (plane-stress corrected in 2D)
  double mu;      // shear modulus

  /// Physical gradients G (row a = ∇_x N_a) and det J at reference point xi.
  static void physical_gradients(const Coordinates& Xe, const typename Element::Point& xi,
                                 Eigen::Matrix<double, kNodes, Dim>& G, double& det) {
    const auto dN = Element::gradients(xi);
    const Tensor J = Xe.transpose() * dN;  // J_ij = ∂x_i/∂ξ_j
    det = J.determinant();
    G = dN * J.inverse();  // ∇_x N_a = J⁻ᵀ ∇_ξ N_a, as rows
  }

  /// Displacement gradient H_ij = ∂u_i/∂x_j from element DOFs (node-major).
  static Tensor gradient(const Vector& ue, const Eigen::Matrix<double, kNodes, Dim>& G) {
    Tensor H = Tensor::Zero();
    for (int a = 0; a < kNodes; ++a) H += ue.template segment<Dim>(a * Dim) * G.row(a);
    return H;
  }

  Tensor stress(const Tensor& H) const {
    return lambda * H.trace() * Tensor::Identity() + mu * (H + H.transpose());
  }

  /// K_e = Σ_q w_q Bᵀ C B det J over the 2^Dim Gauss points (full integration).
  Matrix stiffness(const Coordinates& Xe) const {
    Matrix K = Matrix::Zero();
    Eigen::Matrix<double, kNodes, Dim> G;
    double det;
    for (const auto& [xi, w] : Element::quadrature()) {
      physical_gradients(Xe, xi, G, det);
      // Exploit isotropy: K_ab,ij = (λ G_ai G_bj + μ G_aj G_bi + μ δ_ij G_a·G_b) w det J.
      const Eigen::Matrix<double, kNodes, kNodes> GG = G * G.transpose();
      const double s = w * det;
      for (int a = 0; a < kNodes; ++a)
        for (int b = 0; b < kNodes; ++b)
          for (int i = 0; i < Dim; ++i)
            for (int j = 0; j < Dim; ++j)
              K(a * Dim + i, b * Dim + j) +=
                  s * (lambda * G(a, i) * G(b, j) + mu * G(a, j) * G(b, i) + (i == j ? mu * GG(a, b) : 0.0));
    }
    return K;
  }

  /// ∂(p_eᵀ K_e(X) u_e)/∂X_e (kNodes × Dim). Isoparametric shape calculus: moving node b in
  /// direction c is the velocity θ = e_c N_b, with δ(∇N_a) = −(∇θ)ᵀ∇N_a and δ det J = det J
  /// div θ, so for the bilinear density e = σ(u):∇p,
  ///   ∂/∂X_b = Σ_q w det J (e I − H_pᵀ σ(u) − H_uᵀ σ(p)) ∇N_b   (the Eshelby-type tensor).
  Coordinates energy_coordinate_gradient(const Coordinates& Xe, const Vector& ue, const Vector& pe) const {
    Coordinates g = Coordinates::Zero();
    Eigen::Matrix<double, kNodes, Dim> G;
    double det;
    for (const auto& [xi, w] : Element::quadrature()) {
      physical_gradients(Xe, xi, G, det);
      const Tensor Hu = gradient(ue, G), Hp = gradient(pe, G);
      const Tensor su = stress(Hu), sp = stress(Hp);
      const double e = (su.array() * Hp.array()).sum();
      const Tensor T = e * Tensor::Identity() - Hp.transpose() * su - Hu.transpose() * sp;
      g += (w * det) * G * T.transpose();
    }
    return g;
  }
};

template <class Element>
struct ElasticityDirectional {
  using Kernel = ElasticityKernel<Element>;
  static constexpr int Dim = Element::kDim;
  /// d/dε [K_e(X + ε dX) u_e] (kDofs): the element force's derivative along a node motion dX.
  /// With Θ = ∇θ = Σ_b dX_b ⊗ ∇N_b: δ∇N_a = −Θᵀ∇N_a, δH_u = −H_u Θ, δ det J = det J tr Θ, so
  ///   δf_a = Σ_q w det J [tr(Θ) σ(H_u) − σ(H_u Θ) − σ(H_u) Θᵀ] ∇N_a.
  static typename Kernel::Vector force_derivative(const Kernel& kernel, const typename Kernel::Coordinates& Xe,
                                                  const typename Kernel::Vector& ue,
                                                  const typename Kernel::Coordinates& dXe) {
    typename Kernel::Vector df = Kernel::Vector::Zero();
    Eigen::Matrix<double, Kernel::kNodes, Dim> G;
    double det;
    for (const auto& [xi, w] : Kernel::Element::quadrature()) {
      Kernel::physical_gradients(Xe, xi, G, det);
      const typename Kernel::Tensor Theta = dXe.transpose() * G;  // Θ_kj = Σ_b dX_{b,k} G_{b,j}
      const typename Kernel::Tensor Hu = Kernel::gradient(ue, G);
      const typename Kernel::Tensor sigma = kernel.stress(Hu);
      const typename Kernel::Tensor T = Theta.trace() * sigma - kernel.stress(Hu * Theta) - sigma * Theta.transpose();
      for (int a = 0; a < Kernel::kNodes; ++a)
        df.template segment<Dim>(a * Dim) += (w * det) * T * G.row(a).transpose();
    }
    return df;
  }
};

/// Surface loads on the element's boundary facets (Q1: segments in 2D, quadrilaterals in 3D).
template <class Element>
struct FacetKernel {
  static constexpr int Dim = Element::kDim;
  using Facet = typename Element::Facet;
  static constexpr int kNodes = Facet::kNodes;
  static constexpr int kPoints = Facet::kPoints;
  using Coordinates = Eigen::Matrix<double, kNodes, Dim>;

  /// Gauss point q's shape functions, their parameter derivatives and weight (the loops below).
  struct Point {
    Eigen::Matrix<double, kNodes, 1> N;
    Eigen::Matrix<double, kNodes, Dim - 1> dN;
    double w = 0.0;
  };
  static Point point(int q) {
    Point p;
    Facet::shape(q, p.N, p.dN, p.w);
    return p;
  }

  /// Nodal forces ∫ N_a t dS (kNodes × Dim) for a constant traction t.
  static Coordinates load(const Coordinates& Xf, const Eigen::Matrix<double, Dim, 1>& t) {
    Coordinates f = Coordinates::Zero();
    for (int q = 0; q < kPoints; ++q) {
      const auto [N, dN, w] = point(q);
      f += (w * area_density(Xf, dN)) * N * t.transpose();
    }
    return f;
  }

  /// ∂/∂X_f of ∫ (p_h · t) dS (kNodes × Dim): only dS depends on X.
  /// 2D: δ|x_η| = τ̂·δx_η; 3D: δ|x_1 × x_2| = n̂·(δx_1 × x_2 + x_1 × δx_2).
  static Coordinates load_coordinate_gradient(const Coordinates& Xf, const Eigen::Matrix<double, Dim, 1>& t,
                                              const Coordinates& pf) {
    Coordinates g = Coordinates::Zero();
    for (int q = 0; q < kPoints; ++q) {
      const auto [N, dN, w] = point(q);
      const double pt = (N.transpose() * pf * t)(0);
      if constexpr (Dim == 2) {
        const Eigen::Vector2d x1 = Xf.transpose() * dN.col(0);
        const Eigen::Vector2d tau = x1 / x1.norm();
        for (int b = 0; b < kNodes; ++b) g.row(b) += w * pt * dN(b, 0) * tau.transpose();
      } else {
        const Eigen::Vector3d x1 = Xf.transpose() * dN.col(0), x2 = Xf.transpose() * dN.col(1);
        const Eigen::Vector3d n = x1.cross(x2).normalized();
        const Eigen::Vector3d c1 = x2.cross(n), c2 = n.cross(x1);
        for (int b = 0; b < kNodes; ++b) g.row(b) += w * pt * (dN(b, 0) * c1 + dN(b, 1) * c2).transpose();
      }
    }
    return g;
  }

  /// d/dε of load(Xf + ε dXf, t): only the area density changes.
  static Coordinates load_derivative(const Coordinates& Xf, const Eigen::Matrix<double, Dim, 1>& t, const Coordinates& dXf) {
    Coordinates f = Coordinates::Zero();
    for (int q = 0; q < kPoints; ++q) {
      const auto [N, dN, w] = point(q);
      double d_density;
      if constexpr (Dim == 2) {
        const Eigen::Vector2d x1 = Xf.transpose() * dN.col(0), dx1 = dXf.transpose() * dN.col(0);
        d_density = x1.dot(dx1) / x1.norm();
      } else {
        const Eigen::Vector3d x1 = Xf.transpose() * dN.col(0), x2 = Xf.transpose() * dN.col(1);
        const Eigen::Vector3d dx1 = dXf.transpose() * dN.col(0), dx2 = dXf.transpose() * dN.col(1);
        const Eigen::Vector3d n = x1.cross(x2).normalized();
        d_density = n.dot(dx1.cross(x2) + x1.cross(dx2));
      }
      f += (w * d_density) * N * t.transpose();
    }
    return f;
  }

  static double area_density(const Coordinates& Xf, const Eigen::Matrix<double, kNodes, Dim - 1>& dN) {
    if constexpr (Dim == 2) {
      return (Xf.transpose() * dN.col(0)).norm();
    } else {
      const Eigen::Vector3d x1 = Xf.transpose() * dN.col(0), x2 = Xf.transpose() * dN.col(1);
      return x1.cross(x2).norm();
    }
  }
};

}  // namespace frictopt::fem::detail
