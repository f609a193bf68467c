// SPDX-License-Identifier: MIT
// The structured reference grid of the body and its vertical morph X(α) = X_ref + V α
// (spec 01, §2.6 A-MESH; 3D as in §3).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <string>
#include <vector>

#include "frictopt/mesh/face.hpp"
#include "frictopt/shape/bezier_shape.hpp"

namespace frictopt::mesh {

/// Grid resolution: cells along x1, (x2 in 3D,) and the vertical direction.
struct GridResolution {
  std::array<int, 3> cells{1, 1, 1};  ///< (n1, n2, n_vertical); n2 is ignored in 2D
  /// Vertical bias toward the contact surface: layer k sits at ŝ_k = (k/n_vertical)^grading,
  /// so grading > 1 refines near the bottom where the contact stresses concentrate. In [1, 10].
  double grading = 1.0;
};

/// Row-major element connectivity: one element per row, nodes in VTK order.
using Connectivity = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Structured mesh of bilinear quadrilaterals (2D) or trilinear hexahedra (3D).
///
/// Why Q1 and not simplices: the morph moves nodes only vertically along fixed columns, so a
/// structured Q1 grid stays well shaped for every admissible design, needs no remeshing, has
/// half (2D) or a sixth (3D) as many elements as the split simplices, and resolves bending and
/// Hertzian stress gradients better per unknown; one tensor-product kernel serves 2D and 3D.
///
/// Node numbering: column c = i1 + (n1+1)·i2 (i2 = 0 in 2D), node = c + num_columns·k with
/// layer k = 0 (bottom, Γ_c) .. n_vertical (top). Coordinates of a node in column c, layer k:
///   x' = (i1·a/n1, i2·b/n2),   x_dim = ŝ_k·C4 + (1 − ŝ_k)·G_α(x')        (spec 01, (A-MESH))
/// so X(α) = X_ref + V α with X_ref(x_dim) = ŝ_k·C4 and V[(node, dim−1), :] = (1−ŝ_k)·basis(x').
/// Degrees of freedom / coordinates are node-major: index = node·dim + component.
class StructuredMesh {
 public:
  /// `shape` gives the bottom surface (its extents are the body's a, b); `height` is C4.
  /// Throws InvalidInput for a resolution < 1 or a grading outside [1, 10].
  StructuredMesh(const shape::BezierShape& shape, double height, const GridResolution& resolution);

  int dim() const { return dim_; }
  int num_nodes() const { return num_columns_ * (cells_[2] + 1); }
  int num_columns() const { return num_columns_; }
  int num_elements() const { return static_cast<int>(elements_.rows()); }
  int nodes_per_element() const { return dim_ == 2 ? 4 : 8; }
  int num_dofs() const { return dim_ * num_nodes(); }
  std::array<int, 3> cells() const { return cells_; }
  double height() const { return height_; }
  const shape::BezierShape& shape() const { return shape_; }
  /// VTK cell type of the elements: 9 (VTK_QUAD) or 12 (VTK_HEXAHEDRON).
  int vtk_cell_type() const { return dim_ == 2 ? 9 : 12; }

  const Connectivity& elements() const { return elements_; }
  /// Node index of column (i1, i2) in layer k.
  int node(int i1, int i2, int k) const { return i1 + (cells_[0] + 1) * i2 + num_columns_ * k; }
  /// Vertical parameter ŝ_k of layer k.
  double layer_parameter(int k) const { return s_[k]; }

  /// Node positions X(α), num_nodes × dim, in metres.
  Eigen::MatrixXd positions(const Eigen::Ref<const Eigen::VectorXd>& alpha) const;
  /// The constant sparse Jacobian V = ∂X/∂α, (num_nodes·dim) × d, node-major rows.
  const Eigen::SparseMatrix<double>& design_jacobian() const { return V_; }

  /// Nodes on a face, each once, in increasing index order.
  std::vector<int> face_nodes(Face face) const;
  /// Boundary facets of a face: rows of 2 (2D segments) or 4 (3D quads, cyclic order) nodes.
  Connectivity face_facets(Face face) const;
  /// The bottom (Γ_c) nodes, column order, and their in-plane coordinates (num_columns × dim−1).
  std::vector<int> bottom_nodes() const { return face_nodes(Face::kBottom); }
  Eigen::MatrixXd bottom_plane_coordinates() const;

  /// Volume (3D) or area per unit thickness (2D) of the mesh with positions X, by 2×2(×2)
  /// Gauss quadrature of det J (exact for the multilinear geometry of Q1 elements).
  double volume(const Eigen::Ref<const Eigen::MatrixXd>& X) const;

  /// Throws InvalidInput naming the element, its grid position, the design label and det J when
  /// an element of X is inverted or degenerate (det J at a corner <= 1e-12 × the element's
  /// reference det J). `design_label` says which design is meant, e.g. "initial design" or
  /// "design 12".
  void check_quality(const Eigen::Ref<const Eigen::MatrixXd>& X, const std::string& design_label) const;

 private:
  int dim_;
  shape::BezierShape shape_;
  double height_;
  std::array<int, 3> cells_;
  int num_columns_;
  std::vector<double> s_;
  Eigen::MatrixXd reference_;  // X_ref: num_nodes × dim
  Eigen::SparseMatrix<double> V_;
  Connectivity elements_;
};

}  // namespace frictopt::mesh
