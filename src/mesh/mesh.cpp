// SPDX-License-Identifier: MIT
#include "frictopt/mesh/mesh.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "frictopt/core/error.hpp"
#include "frictopt/mesh/elements.hpp"

namespace frictopt::mesh {

Mesh::Mesh(ElementKind kind, Eigen::MatrixXd reference_positions, Connectivity elements,
           Eigen::SparseMatrix<double> design_jacobian, std::map<std::string, BoundarySet, std::less<>> boundaries,
           ElementDiagnostics diagnostics)
    : kind_(kind),
      reference_(std::move(reference_positions)),
      elements_(std::move(elements)),
      V_(std::move(design_jacobian)),
      boundaries_(std::move(boundaries)),
      diagnostics_(std::move(diagnostics)) {
  const int d = dim();
  if (reference_.cols() != d)
    throw InvalidInput(fmt::format("mesh: reference positions have {} columns; expected {} for {} cells",
                                   reference_.cols(), d, to_string(kind_)));
  if (elements_.rows() > 0 && elements_.cols() != nodes_per_element())
    throw InvalidInput(fmt::format("mesh: cells have {} nodes; expected {} for {} cells", elements_.cols(),
                                   nodes_per_element(), to_string(kind_)));
  const auto check_indices = [&](const Connectivity& c, const std::string& what) {
    if (c.size() > 0 && (c.minCoeff() < 0 || c.maxCoeff() >= num_nodes()))
      throw InvalidInput(fmt::format("mesh: {} refer to node {}; expected indices in [0, {})", what,
                                     c.minCoeff() < 0 ? c.minCoeff() : c.maxCoeff(), num_nodes()));
  };
  check_indices(elements_, "cells");
  if (V_.rows() != static_cast<Eigen::Index>(num_dofs()))
    throw InvalidInput(fmt::format("mesh: the design Jacobian has {} rows; expected num_nodes·dim = {}", V_.rows(),
                                   num_dofs()));
  for (const auto& [name, set] : boundaries_) {
    if (set.facets.rows() > 0 && set.facets.cols() != nodes_per_facet(kind_))
      throw InvalidInput(fmt::format("mesh: boundary '{}' has facets of {} nodes; expected {}", name,
                                     set.facets.cols(), nodes_per_facet(kind_)));
    check_indices(set.facets, "the facets of boundary '" + name + "'");
    std::vector<int> facet_nodes(set.facets.data(), set.facets.data() + set.facets.size());
    std::sort(facet_nodes.begin(), facet_nodes.end());
    facet_nodes.erase(std::unique(facet_nodes.begin(), facet_nodes.end()), facet_nodes.end());
    if (facet_nodes != set.nodes)
      throw InvalidInput(fmt::format("mesh: boundary '{}' lists {} nodes; expected the {} distinct nodes of its "
                                     "facets, in increasing order",
                                     name, set.nodes.size(), facet_nodes.size()));
  }
}

Eigen::MatrixXd Mesh::positions(const Eigen::Ref<const Eigen::VectorXd>& alpha) const {
  FRICTOPT_ASSERT(alpha.size() == V_.cols(), "design size");
  const int d = dim();
  Eigen::MatrixXd X = reference_;
  const Eigen::VectorXd shift = V_ * alpha;
  for (int n = 0; n < num_nodes(); ++n) X.row(n) += shift.segment(n * d, d).transpose();
  return X;
}

const BoundarySet& Mesh::boundary(std::string_view name) const {
  const auto it = boundaries_.find(name);
  if (it == boundaries_.end()) {
    std::string names;
    for (const auto& [known, set] : boundaries_) names += (names.empty() ? "" : ", ") + known;
    throw InvalidInput(fmt::format("boundary '{}' is not part of this {}D mesh; expected one of {}", name, dim(),
                                   names));
  }
  return it->second;
}

std::vector<std::string> Mesh::boundary_names() const {
  std::vector<std::string> names;
  for (const auto& [name, set] : boundaries_) names.push_back(name);
  return names;
}

namespace {
template <class Element>
double element_volume_sum(const Connectivity& elements, const Eigen::Ref<const Eigen::MatrixXd>& X) {
  constexpr int Dim = Element::kDim;
  const auto rule = Element::quadrature();
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

template <class Element>
void check_elements(const Connectivity& elements, const ElementDiagnostics& diagnostics,
                    const Eigen::Ref<const Eigen::MatrixXd>& X, const std::string& label) {
  constexpr int Dim = Element::kDim;
  const auto corners = Element::corners();
  Eigen::Matrix<double, Element::kNodes, Dim> Xe;
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    for (int a = 0; a < Element::kNodes; ++a) Xe.row(a) = X.row(elements(e, a));
    // Scale: the reference element's size (edge lengths) so the test is unit-free.
    const double size = (Xe.colwise().maxCoeff() - Xe.colwise().minCoeff()).prod() / std::pow(2.0, Dim);
    for (int a = 0; a < Element::kNodes; ++a) {
      const Eigen::Matrix<double, Dim, 1> xi = corners.row(a).transpose();
      const double det = (Xe.transpose() * Element::gradients(xi)).determinant();
      if (!(det > 1e-12 * size)) {
        const std::string where = diagnostics.location ? " (" + diagnostics.location(e) + ")" : "";
        throw InvalidInput(fmt::format("element {}{} is {} for the {} (det J = {:.3e} at corner {}); expected det J > 0{}",
                                       e, where, det < 0 ? "inverted" : "degenerate", label, det, a,
                                       diagnostics.inverted_hint));
      }
    }
  }
}
template <class Element>
double smallest_scaled_jacobian(const Connectivity& elements, const Eigen::Ref<const Eigen::MatrixXd>& X) {
  constexpr int Dim = Element::kDim;
  Eigen::Matrix<double, Element::kNodes, Dim> Xe;
  double smallest = 1.0;
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    for (int a = 0; a < Element::kNodes; ++a) Xe.row(a) = X.row(elements(e, a));
    for (int a = 0; a < Element::kNodes; ++a) smallest = std::min(smallest, Element::scaled_jacobian_at_corner(Xe, a));
  }
  return smallest;
}
}  // namespace

double Mesh::min_scaled_jacobian(const Eigen::Ref<const Eigen::MatrixXd>& X) const {
  return with_element(kind_, [&](auto element) { return smallest_scaled_jacobian<decltype(element)>(elements_, X); });
}

Mesh Mesh::with_design_jacobian(Eigen::SparseMatrix<double> design_jacobian) const {
  return Mesh(kind_, reference_, elements_, std::move(design_jacobian), boundaries_, diagnostics_);
}

double Mesh::volume(const Eigen::Ref<const Eigen::MatrixXd>& X) const {
  return with_element(kind_, [&](auto element) { return element_volume_sum<decltype(element)>(elements_, X); });
}

void Mesh::check_quality(const Eigen::Ref<const Eigen::MatrixXd>& X, const std::string& design_label) const {
  with_element(kind_, [&](auto element) { check_elements<decltype(element)>(elements_, diagnostics_, X, design_label); });
}

}  // namespace frictopt::mesh
