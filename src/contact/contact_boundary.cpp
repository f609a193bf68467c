// SPDX-License-Identifier: MIT
#include "frictopt/contact/contact_boundary.hpp"

#include <cmath>
#include <map>

#include <Eigen/LU>

#include <fmt/format.h>

#include "frictopt/core/error.hpp"
#include "frictopt/mesh/q1_element.hpp"

namespace frictopt::contact {

bool Foundation::is_standard(int dim) const {
  if (offset != 0.0) return false;
  if (frame.normal.size() == 0) return true;
  const mesh::PlaneFrame s = mesh::PlaneFrame::standard(dim);
  return frame.normal.size() == dim && frame.normal == s.normal && frame.tangents == s.tangents;
}

ContactBoundary::ContactBoundary(const mesh::Mesh& mesh, const fem::DofMap& dofs, std::string_view surface,
                                 Foundation foundation)
    : dim_(mesh.dim()), num_free_(dofs.num_free()), foundation_(std::move(foundation)) {
  if (foundation_.frame.normal.size() == 0) foundation_.frame = mesh::PlaneFrame::standard(dim_);
  if (foundation_.frame.dim() != dim_ || foundation_.frame.tangents.rows() != dim_ ||
      foundation_.frame.tangents.cols() != dim_ - 1)
    throw InvalidInput(fmt::format("foundation: a frame of dimension {} for a {}D body; expected {}",
                                   foundation_.frame.dim(), dim_, dim_));
  if (!std::isfinite(foundation_.offset))
    throw InvalidInput(fmt::format("foundation.offset = {}; expected a finite distance", foundation_.offset));
  standard_ = foundation_.is_standard(dim_);
  // F: rows −t_kᵀ, nᵀ (G u = (−u_t, u_ν) per node in the foundation's frame).
  rows_.resize(dim_, dim_);
  for (int k = 0; k < dim_ - 1; ++k) rows_.row(k) = -foundation_.frame.tangents.col(k).transpose();
  rows_.row(dim_ - 1) = foundation_.frame.normal.transpose();
  const mesh::BoundarySet& contact_surface = mesh.boundary(surface);
  const std::vector<int>& bottom = contact_surface.nodes;
  // In-plane coordinates in the foundation's frame (the standard one: x1 (, x2), bit for bit).
  Eigen::MatrixXd plane(static_cast<Eigen::Index>(bottom.size()), dim_ - 1);
  for (std::size_t k = 0; k < bottom.size(); ++k)
    plane.row(static_cast<Eigen::Index>(k)) =
        standard_ ? Eigen::RowVectorXd(mesh.reference_positions().row(bottom[k]).head(dim_ - 1))
                  : Eigen::RowVectorXd(mesh.reference_positions().row(bottom[k]) * foundation_.frame.tangents);
  std::vector<Eigen::Index> kept;
  for (std::size_t k = 0; k < bottom.size(); ++k) {
    bool all_free = true;
    for (int c = 0; c < dim_; ++c) all_free = all_free && dofs.is_free(bottom[k] * dim_ + c);
    if (!all_free) continue;
    nodes_.push_back(bottom[k]);
    kept.push_back(static_cast<Eigen::Index>(k));
    for (int c = 0; c < dim_; ++c) free_dofs_.push_back(dofs.free_index(bottom[k] * dim_ + c));
  }
  plane_.resize(static_cast<Eigen::Index>(kept.size()), dim_ - 1);
  for (std::size_t i = 0; i < kept.size(); ++i) plane_.row(static_cast<Eigen::Index>(i)) = plane.row(kept[i]);

  std::map<int, Eigen::Index> index;
  for (std::size_t i = 0; i < nodes_.size(); ++i) index[nodes_[i]] = static_cast<Eigen::Index>(i);
  std::map<int, Eigen::Index> bottom_row;
  for (std::size_t k = 0; k < bottom.size(); ++k) bottom_row[bottom[k]] = static_cast<Eigen::Index>(k);
  areas_ = Eigen::VectorXd::Zero(num_nodes());
  const mesh::Connectivity& facets = contact_surface.facets;
  for (Eigen::Index f = 0; f < facets.rows(); ++f) {
    const auto x = [&](Eigen::Index k) { return plane.row(bottom_row.at(facets(f, k))); };
    if (facets.cols() == 3) {
      // A linear triangle (a tetrahedron's face): ∫ N_a = area/3 on the projected triangle.
      const double area = 0.5 * std::abs((x(1)(0) - x(0)(0)) * (x(2)(1) - x(0)(1)) -
                                         (x(1)(1) - x(0)(1)) * (x(2)(0) - x(0)(0)));
      for (Eigen::Index k = 0; k < 3; ++k) {
        const auto it = index.find(facets(f, k));
        if (it != index.end()) areas_(it->second) += area / 3.0;
      }
      continue;
    }
    // (Exact equality: a tilted frame's rounding sends a grid facet to the general formula,
    // which is exact for parallelograms too.)
    const bool parallelogram = dim_ == 2 || x(0) + x(2) == x(1) + x(3);
    if (parallelogram) {
      // Projected length (2D) or parallelogram area |e1 × e3| (3D) of the facet in the x'-plane,
      // shared equally (∫N_a = area/4 on a parallelogram); for the grid's axis-parallel facets
      // the second product is exactly zero.
      const double area = dim_ == 2 ? std::abs(x(1)(0) - x(0)(0))
                                    : std::abs((x(1)(0) - x(0)(0)) * (x(3)(1) - x(0)(1)) -
                                               (x(1)(1) - x(0)(1)) * (x(3)(0) - x(0)(0)));
      for (Eigen::Index k = 0; k < facets.cols(); ++k) {
        const auto it = index.find(facets(f, k));
        if (it != index.end()) areas_(it->second) += area / static_cast<double>(facets.cols());
      }
      continue;
    }
    // A general quadrilateral of an imported mesh: node a gets ∫ N_a over the projected
    // bilinear facet (2 × 2 Gauss, exact: N_a·det J has degree <= 2 in each variable), the consistent nodal weight of a pressure on Γ_c.
    Eigen::Matrix<double, 4, 2> corners;
    for (int k = 0; k < 4; ++k) corners.row(k) = x(k);
    Eigen::Matrix<double, 4, 1> N;
    Eigen::Matrix<double, 4, 2> dN;
    for (int q = 0; q < mesh::Q1Facet<3>::kPoints; ++q) {
      double weight = 0.0;
      mesh::Q1Facet<3>::shape(q, N, dN, weight);
      const double det = std::abs((corners.transpose() * dN).determinant());
      for (int k = 0; k < 4; ++k) {
        const auto it = index.find(facets(f, k));
        if (it != index.end()) areas_(it->second) += weight * det * N(k);
      }
    }
  }
}

Eigen::VectorXd ContactBoundary::gaps(const Eigen::Ref<const Eigen::MatrixXd>& X) const {
  Eigen::VectorXd g(num_nodes());
  if (standard_) {
    for (Eigen::Index i = 0; i < num_nodes(); ++i) g(i) = X(nodes_[static_cast<std::size_t>(i)], dim_ - 1);
    return g;
  }
  for (Eigen::Index i = 0; i < num_nodes(); ++i)
    g(i) = X.row(nodes_[static_cast<std::size_t>(i)]).dot(foundation_.frame.normal.transpose()) - foundation_.offset;
  return g;
}

Eigen::MatrixXd ContactBoundary::gap_jacobian(const mesh::Mesh& mesh) const {
  const Eigen::SparseMatrix<double, Eigen::RowMajor> V = mesh.design_jacobian();
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(num_nodes(), V.cols());
  for (Eigen::Index i = 0; i < num_nodes(); ++i) {
    const Eigen::Index node = static_cast<Eigen::Index>(nodes_[static_cast<std::size_t>(i)]);
    if (standard_) {
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(V, node * dim_ + dim_ - 1); it; ++it)
        B(i, it.col()) = it.value();
      continue;
    }
    // ∂g_i/∂α = n·∂X_i/∂α = Σ_c n_c V(node·dim + c, :).
    for (int c = 0; c < dim_; ++c)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(V, node * dim_ + c); it; ++it)
        B(i, it.col()) += foundation_.frame.normal(c) * it.value();
  }
  return B;
}

void ContactBoundary::add_transpose_times(const Eigen::Ref<const Eigen::VectorXd>& z,
                                          Eigen::Ref<Eigen::VectorXd> w_free) const {
  if (standard_) {
    for (Eigen::Index k = 0; k < num_unknowns(); ++k) {
      const bool normal = (k % dim_) == dim_ - 1;
      w_free(free_dofs_[static_cast<std::size_t>(k)]) += normal ? z(k) : -z(k);
    }
    return;
  }
  // Node i's block: (Gᵀz)_node = Fᵀ z_i on its dim DOFs.
  for (Eigen::Index i = 0; i < num_nodes(); ++i)
    for (int c = 0; c < dim_; ++c) {
      double sum = 0.0;
      for (int r = 0; r < dim_; ++r) sum += rows_(r, c) * z(dim_ * i + r);
      w_free(free_dofs_[static_cast<std::size_t>(dim_ * i + c)]) += sum;
    }
}

Eigen::VectorXd ContactBoundary::times(const Eigen::Ref<const Eigen::VectorXd>& v_free) const {
  Eigen::VectorXd y(num_unknowns());
  if (standard_) {
    for (Eigen::Index k = 0; k < num_unknowns(); ++k) {
      const bool normal = (k % dim_) == dim_ - 1;
      const double v = v_free(free_dofs_[static_cast<std::size_t>(k)]);
      y(k) = normal ? v : -v;
    }
    return y;
  }
  for (Eigen::Index i = 0; i < num_nodes(); ++i)
    for (int r = 0; r < dim_; ++r) {
      double sum = 0.0;
      for (int c = 0; c < dim_; ++c) sum += rows_(r, c) * v_free(free_dofs_[static_cast<std::size_t>(dim_ * i + c)]);
      y(dim_ * i + r) = sum;
    }
  return y;
}

Eigen::VectorXd ContactBoundary::times_full(const Eigen::Ref<const Eigen::VectorXd>& v_full) const {
  Eigen::VectorXd y(num_unknowns());
  for (Eigen::Index i = 0; i < num_nodes(); ++i) {
    const int node = nodes_[static_cast<std::size_t>(i)];
    if (standard_) {
      for (int c = 0; c < dim_; ++c) {
        const double v = v_full(node * dim_ + c);
        y(dim_ * i + c) = c == dim_ - 1 ? v : -v;
      }
      continue;
    }
    for (int r = 0; r < dim_; ++r) {
      double sum = 0.0;
      for (int c = 0; c < dim_; ++c) sum += rows_(r, c) * v_full(node * dim_ + c);
      y(dim_ * i + r) = sum;
    }
  }
  return y;
}

Eigen::VectorXd ContactBoundary::tangential_displacements(const Eigen::Ref<const Eigen::VectorXd>& u_full) const {
  const Eigen::VectorXd gu = times_full(u_full);  // (−u_t, u_ν) per node
  Eigen::VectorXd ut((dim_ - 1) * num_nodes());
  for (Eigen::Index i = 0; i < num_nodes(); ++i)
    for (int c = 0; c < dim_ - 1; ++c) ut((dim_ - 1) * i + c) = -gu(dim_ * i + c);
  return ut;
}

Eigen::SparseMatrix<double> ContactBoundary::matrix() const {
  std::vector<Eigen::Triplet<double>> t;
  for (Eigen::Index k = 0; k < num_unknowns(); ++k) {
    if (standard_) {
      t.emplace_back(k, free_dofs_[static_cast<std::size_t>(k)], (k % dim_) == dim_ - 1 ? 1.0 : -1.0);
      continue;
    }
    const Eigen::Index i = k / dim_;
    const int r = static_cast<int>(k % dim_);
    for (int c = 0; c < dim_; ++c)
      if (rows_(r, c) != 0.0) t.emplace_back(k, free_dofs_[static_cast<std::size_t>(dim_ * i + c)], rows_(r, c));
  }
  Eigen::SparseMatrix<double> G(num_unknowns(), num_free_);
  G.setFromTriplets(t.begin(), t.end());
  return G;
}

}  // namespace frictopt::contact
