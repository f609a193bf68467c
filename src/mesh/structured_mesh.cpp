// SPDX-License-Identifier: MIT
#include "frictopt/mesh/structured_mesh.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "frictopt/core/error.hpp"
#include "frictopt/mesh/q1_element.hpp"

namespace frictopt::mesh {

StructuredMesh::StructuredMesh(const shape::BezierShape& shape, double height,
                               const GridResolution& resolution)
    : dim_(shape.dim()), shape_(shape), height_(height), cells_(resolution.cells) {
  if (dim_ == 2) cells_[1] = 0;  // no x2 direction: one column row
  for (int c = 0; c < 3; ++c) {
    if (c == 1 && dim_ == 2) continue;
    if (cells_[c] < 1)
      throw InvalidInput(fmt::format("mesh.cells[{}] = {}; expected >= 1", c == 2 && dim_ == 2 ? 1 : c,
                                     cells_[c]));
  }
  if (!(resolution.grading >= 1.0 && resolution.grading <= 10.0))
    throw InvalidInput(fmt::format("mesh.grading = {}; expected within [1, 10]", resolution.grading));
  if (!(height > 0)) throw InvalidInput(fmt::format("geometry.height = {}; expected > 0", height));

  const int n1 = cells_[0], n2 = cells_[1], nv = cells_[2];
  num_columns_ = (n1 + 1) * (n2 + 1);
  s_.resize(nv + 1);
  for (int k = 0; k <= nv; ++k) s_[k] = std::pow(static_cast<double>(k) / nv, resolution.grading);

  const auto extent = shape.extents();
  const int d = shape.num_controls();
  reference_.resize(num_nodes(), dim_);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(num_nodes()) * d);
  for (int i2 = 0; i2 <= n2; ++i2)
    for (int i1 = 0; i1 <= n1; ++i1) {
      Eigen::VectorXd x_plane(dim_ - 1);
      x_plane(0) = extent[0] * i1 / n1;
      if (dim_ == 3) x_plane(1) = extent[1] * i2 / n2;
      const Eigen::VectorXd basis = shape.basis(x_plane);
      for (int k = 0; k <= nv; ++k) {
        const int n = node(i1, i2, k);
        reference_.row(n).head(dim_ - 1) = x_plane.transpose();
        reference_(n, dim_ - 1) = s_[k] * height;
        if (k == nv) continue;  // the top does not move: (1 − ŝ) = 0
        for (int j = 0; j < d; ++j)
          triplets.emplace_back(n * dim_ + dim_ - 1, j, (1.0 - s_[k]) * basis(j));
      }
    }
  V_.resize(num_dofs(), d);
  V_.setFromTriplets(triplets.begin(), triplets.end());

  const int n2_cells = dim_ == 3 ? n2 : 1;
  elements_.resize(static_cast<Eigen::Index>(n1) * n2_cells * nv, nodes_per_element());
  int e = 0;
  for (int k = 0; k < nv; ++k)
    for (int i2 = 0; i2 < n2_cells; ++i2)
      for (int i1 = 0; i1 < n1; ++i1, ++e) {
        if (dim_ == 2) {
          elements_.row(e) << node(i1, 0, k), node(i1 + 1, 0, k), node(i1 + 1, 0, k + 1),
              node(i1, 0, k + 1);
        } else {
          elements_.row(e) << node(i1, i2, k), node(i1 + 1, i2, k), node(i1 + 1, i2 + 1, k),
              node(i1, i2 + 1, k), node(i1, i2, k + 1), node(i1 + 1, i2, k + 1),
              node(i1 + 1, i2 + 1, k + 1), node(i1, i2 + 1, k + 1);
        }
      }
}

Eigen::MatrixXd StructuredMesh::positions(const Eigen::Ref<const Eigen::VectorXd>& alpha) const {
  FRICTOPT_ASSERT(alpha.size() == V_.cols(), "design size");
  Eigen::MatrixXd X = reference_;
  const Eigen::VectorXd shift = V_ * alpha;
  for (int n = 0; n < num_nodes(); ++n) X.row(n) += shift.segment(n * dim_, dim_).transpose();
  return X;
}

std::vector<int> StructuredMesh::face_nodes(Face face) const {
  if (dim_ == 2 && (face == Face::kFront || face == Face::kBack))
    throw InvalidInput(fmt::format("face '{}' exists only in 3D", to_string(face)));
  const int n1 = cells_[0], n2 = cells_[1], nv = cells_[2];
  std::vector<int> nodes;
  for (int k = 0; k <= nv; ++k)
    for (int i2 = 0; i2 <= n2; ++i2)
      for (int i1 = 0; i1 <= n1; ++i1) {
        const bool on = (face == Face::kLeft && i1 == 0) || (face == Face::kRight && i1 == n1) ||
                        (face == Face::kFront && i2 == 0) || (face == Face::kBack && i2 == n2) ||
                        (face == Face::kBottom && k == 0) || (face == Face::kTop && k == nv);
        if (on) nodes.push_back(node(i1, i2, k));
      }
  return nodes;
}

Connectivity StructuredMesh::face_facets(Face face) const {
  if (dim_ == 2 && (face == Face::kFront || face == Face::kBack))
    throw InvalidInput(fmt::format("face '{}' exists only in 3D", to_string(face)));
  const int n1 = cells_[0], n2 = cells_[1], nv = cells_[2];
  std::vector<std::array<int, 4>> facets;
  if (dim_ == 2) {
    if (face == Face::kLeft || face == Face::kRight) {
      const int i1 = face == Face::kLeft ? 0 : n1;
      for (int k = 0; k < nv; ++k) facets.push_back({node(i1, 0, k), node(i1, 0, k + 1), 0, 0});
    } else {
      const int k = face == Face::kBottom ? 0 : nv;
      for (int i1 = 0; i1 < n1; ++i1) facets.push_back({node(i1, 0, k), node(i1 + 1, 0, k), 0, 0});
    }
  } else if (face == Face::kLeft || face == Face::kRight) {
    const int i1 = face == Face::kLeft ? 0 : n1;
    for (int k = 0; k < nv; ++k)
      for (int i2 = 0; i2 < n2; ++i2)
        facets.push_back({node(i1, i2, k), node(i1, i2 + 1, k), node(i1, i2 + 1, k + 1),
                          node(i1, i2, k + 1)});
  } else if (face == Face::kFront || face == Face::kBack) {
    const int i2 = face == Face::kFront ? 0 : n2;
    for (int k = 0; k < nv; ++k)
      for (int i1 = 0; i1 < n1; ++i1)
        facets.push_back({node(i1, i2, k), node(i1 + 1, i2, k), node(i1 + 1, i2, k + 1),
                          node(i1, i2, k + 1)});
  } else {
    const int k = face == Face::kBottom ? 0 : nv;
    for (int i2 = 0; i2 < n2; ++i2)
      for (int i1 = 0; i1 < n1; ++i1)
        facets.push_back({node(i1, i2, k), node(i1 + 1, i2, k), node(i1 + 1, i2 + 1, k),
                          node(i1, i2 + 1, k)});
  }
  const int width = dim_ == 2 ? 2 : 4;
  Connectivity out(static_cast<Eigen::Index>(facets.size()), width);
  for (std::size_t f = 0; f < facets.size(); ++f)
    for (int j = 0; j < width; ++j) out(static_cast<Eigen::Index>(f), j) = facets[f][j];
  return out;
}

Eigen::MatrixXd StructuredMesh::bottom_plane_coordinates() const {
  const std::vector<int> nodes = bottom_nodes();
  Eigen::MatrixXd P(static_cast<Eigen::Index>(nodes.size()), dim_ - 1);
  for (std::size_t i = 0; i < nodes.size(); ++i)
    P.row(static_cast<Eigen::Index>(i)) = reference_.row(nodes[i]).head(dim_ - 1);
  return P;
}

namespace {
template <int Dim>
double element_volume_sum(const Connectivity& elements, const Eigen::Ref<const Eigen::MatrixXd>& X) {
  using Element = Q1Element<Dim>;
  const auto rule = Element::gauss2();
  double volume = 0.0;
  Eigen::Matrix<double, Element::kNodes, Dim> Xe;
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    for (int a = 0; a < Element::kNodes; ++a) Xe.row(a) = X.row(elements(e, a));
    for (const auto& [xi, w] : rule) {
      const Eigen::Matrix<double, Dim, Dim> J = Xe.transpose() * Element::gradients(xi);
      volume += w * J.determinant();
    }
  }
  return volume;
}

template <int Dim>
void check_elements(const StructuredMesh& mesh, const Eigen::Ref<const Eigen::MatrixXd>& X,
                    const std::string& label) {
  using Element = Q1Element<Dim>;
  const auto corners = Element::corners();
  const Connectivity& elements = mesh.elements();
  Eigen::Matrix<double, Element::kNodes, Dim> Xe;
  const auto cells = mesh.cells();
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    for (int a = 0; a < Element::kNodes; ++a) Xe.row(a) = X.row(elements(e, a));
    // Scale: the reference element's size (edge lengths) so the test is unit-free.
    const double size = (Xe.colwise().maxCoeff() - Xe.colwise().minCoeff()).prod() / std::pow(2.0, Dim);
    for (int a = 0; a < Element::kNodes; ++a) {
      const Eigen::Matrix<double, Dim, 1> xi = corners.row(a).transpose();
      const double det = (Xe.transpose() * Element::gradients(xi)).determinant();
      if (!(det > 1e-12 * size)) {
        const int n1 = cells[0], n2 = Dim == 3 ? cells[1] : 1;
        const int i1 = static_cast<int>(e % n1), i2 = static_cast<int>((e / n1) % n2),
                  k = static_cast<int>(e / (static_cast<Eigen::Index>(n1) * n2));
        throw InvalidInput(fmt::format(
            "element {} (column {}{}, layer {}) is {} for the {} (det J = {:.3e} at corner {}); "
            "expected det J > 0 — is a control height at or above geometry.height?",
            e, i1, Dim == 3 ? fmt::format(",{}", i2) : "", k, det < 0 ? "inverted" : "degenerate",
            label, det, a));
      }
    }
  }
}
}  // namespace

double StructuredMesh::volume(const Eigen::Ref<const Eigen::MatrixXd>& X) const {
  return dim_ == 2 ? element_volume_sum<2>(elements_, X) : element_volume_sum<3>(elements_, X);
}

void StructuredMesh::check_quality(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                   const std::string& design_label) const {
  if (dim_ == 2)
    check_elements<2>(*this, X, design_label);
  else
    check_elements<3>(*this, X, design_label);
}

}  // namespace frictopt::mesh
