// SPDX-License-Identifier: MIT
// The body's finite element mesh as a value: nodes, cells of one element kind, named boundary
// sets, and the design motion X(α) = X_ref + V α (docs/theory/problem.md §5). Producers (the
// structured grid today) build it; fem, contact, sensitivity and output read only this type.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/mesh/element_kind.hpp"

namespace frictopt::mesh {

/// Row-major connectivity: one cell (or facet) per row, nodes in VTK order.
using Connectivity = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// A named part of the boundary (deal.II's boundary id, MFEM's boundary attribute): the contact
/// surface Γ_c, a Dirichlet part Γ_u, a loaded part Γ_p.
struct BoundarySet {
  /// Facets, one per row: 2 nodes (2D segments), 4 (3D quadrilaterals of hexahedra, cyclic
  /// order) or 3 (triangles of tetrahedra): ElementKind's facet node count.
  Connectivity facets;
  /// The nodes of the facets, each once, in increasing order.
  std::vector<int> nodes;
};

/// What a producer can add to the messages about a cell (optional): where a cell lies in the
/// producer's own terms, and what usually causes an inverted cell.
struct ElementDiagnostics {
  /// E.g. "column 3,4, layer 0"; empty function: only the cell index is named.
  std::function<std::string(Eigen::Index element)> location;
  /// Appended to the inverted-cell message, e.g. " — is a control height at or above geometry.height?".
  std::string inverted_hint;
};

/// Nodes, cells and named boundary sets of a body, and its design motion.
///
/// Positions are node-major: X is num_nodes × dim [m]; degrees of freedom and flattened
/// coordinates are node·dim + component. The design Jacobian V = ∂X/∂α is constant, so
///   X(α) = X_ref + V α     (V: (num_nodes·dim) × num_design_variables, sparse).
/// Invariants (checked by the constructor): connectivity indices in [0, num_nodes), every cell
/// has nodes_per_element(kind) nodes, V has num_nodes·dim rows, boundary facets have the
/// facet node count of the kind and their node lists are exactly the facets' nodes.
class Mesh {
 public:
  /// Throws InvalidInput naming the part that is inconsistent (see the invariants above).
  Mesh(ElementKind kind, Eigen::MatrixXd reference_positions, Connectivity elements,
       Eigen::SparseMatrix<double> design_jacobian, std::map<std::string, BoundarySet, std::less<>> boundaries,
       ElementDiagnostics diagnostics = {});

  ElementKind element_kind() const { return kind_; }
  int dim() const { return spatial_dimension(kind_); }
  int num_nodes() const { return static_cast<int>(reference_.rows()); }
  int num_elements() const { return static_cast<int>(elements_.rows()); }
  int nodes_per_element() const { return mesh::nodes_per_element(kind_); }
  int num_dofs() const { return dim() * num_nodes(); }
  /// VTK cell type of the cells (9 = VTK_QUAD, 12 = VTK_HEXAHEDRON, 5 = VTK_TRIANGLE, 10 = VTK_TETRA).
  int vtk_cell_type() const { return mesh::vtk_cell_type(kind_); }
  Eigen::Index num_design_variables() const { return V_.cols(); }

  /// X_ref, num_nodes × dim [m].
  const Eigen::MatrixXd& reference_positions() const { return reference_; }
  const Connectivity& elements() const { return elements_; }
  /// The constant V = ∂X/∂α, (num_nodes·dim) × d, node-major rows.
  const Eigen::SparseMatrix<double>& design_jacobian() const { return V_; }
  /// X(α) = X_ref + V α, num_nodes × dim [m].
  Eigen::MatrixXd positions(const Eigen::Ref<const Eigen::VectorXd>& alpha) const;

  bool has_boundary(std::string_view name) const { return boundaries_.find(name) != boundaries_.end(); }
  /// The set called `name`; throws InvalidInput listing the names this mesh has.
  const BoundarySet& boundary(std::string_view name) const;
  /// The names of all boundary sets, sorted.
  std::vector<std::string> boundary_names() const;

  /// Volume (3D) or area per unit thickness (2D) of the mesh at positions X, by the element's
  /// quadrature of det J (exact for the multilinear geometry of Q1 cells and for simplices).
  double volume(const Eigen::Ref<const Eigen::MatrixXd>& X) const;
  /// Throws InvalidInput naming the cell (and the producer's location of it), the design label
  /// and det J when a cell of X is inverted or degenerate (det J at a corner <= 1e-12 × the
  /// cell's reference size). `design_label` says which design is meant, e.g. "design 12".
  void check_quality(const Eigen::Ref<const Eigen::MatrixXd>& X, const std::string& design_label) const;
  /// The smallest scaled Jacobian over the cells' corners at positions X (capped at 1): at a
  /// corner, det of the unit edge directions there; 1 for a rectangle or box and for an
  /// equilateral simplex, 0 for a degenerate corner, < 0 for an inverted one (the Verdict
  /// library's measures for quads, hexes, triangles and tetrahedra).
  double min_scaled_jacobian(const Eigen::Ref<const Eigen::MatrixXd>& X) const;
  /// The same mesh with another design Jacobian V ((num_nodes·dim) × d): how a design motion
  /// (design_extension.hpp) is attached to a mesh read without one.
  Mesh with_design_jacobian(Eigen::SparseMatrix<double> design_jacobian) const;

 private:
  ElementKind kind_;
  Eigen::MatrixXd reference_;
  Connectivity elements_;
  Eigen::SparseMatrix<double> V_;
  std::map<std::string, BoundarySet, std::less<>> boundaries_;
  ElementDiagnostics diagnostics_;
};

}  // namespace frictopt::mesh
