// SPDX-License-Identifier: MIT
// The structured reference grid of a box-like body with a Bézier bottom, and its vertical
// morph X(α) = X_ref + V α (docs/theory/problem.md §5, 2D and 3D): one producer of a mesh::Mesh.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "frictopt/mesh/face.hpp"
#include "frictopt/mesh/grid_resolution.hpp"
#include "frictopt/mesh/mesh.hpp"
#include "frictopt/shape/bezier_shape.hpp"

namespace frictopt::mesh {

/// Counts of a structured grid, in 64 bits so that an absurd resolution is reported rather than
/// wrapped around.
struct StructuredGridSizes {
  std::int64_t columns = 0;   ///< (n1+1)(n2+1), n2 = 0 in 2D
  std::int64_t nodes = 0;     ///< columns · (n_vertical + 1)
  std::int64_t elements = 0;  ///< n1 · n2 · n_vertical (n2 → 1 in 2D)
  std::int64_t dofs = 0;      ///< dim · nodes
};
/// The counts of a dim-dimensional grid of `resolution` (cells as given, each >= 0), computed
/// without allocating anything.
StructuredGridSizes structured_grid_sizes(int dim, const GridResolution& resolution);

/// Structured mesh of bilinear quadrilaterals (2D) or trilinear hexahedra (3D), or of those cells
/// split into P1 triangles or tetrahedra on the same nodes (resolution.element_family).
///
/// Why Q1 and not simplices: the morph moves nodes only vertically along fixed columns, so a
/// structured Q1 grid stays well shaped for every admissible design, needs no remeshing, has
/// half (2D) or a sixth (3D) as many elements as the split simplices, and resolves bending and
/// Hertzian stress gradients better per unknown; one tensor-product kernel serves 2D and 3D.
///
/// Node numbering: column c = i1 + (n1+1)·i2 (i2 = 0 in 2D), node = c + num_columns·k with
/// layer k = 0 (bottom, Γ_c) .. n_vertical (top). Coordinates of a node in column c, layer k:
///   x' = (ξ1_i1, ξ2_i2),   x_dim = ŝ_k·C4 + (1 − ŝ_k)·G_α(x')        (docs/theory/problem.md §5)
/// so X(α) = X_ref + V α with X_ref(x_dim) = ŝ_k·C4 and V[(node, dim−1), :] = (1−ŝ_k)·basis(x').
/// The layers ŝ_k follow resolution.vertical_grading: the power law (k/n_vertical)^grading, or
/// "contact" (equal layers down to fine_depth, geometric growth above; contact_layer_coordinates).
/// The column lines ξ are uniform (ξ1_i = i·a/n1) or, with resolution.growth > 1, graded toward
/// the refinement box (graded_coordinates.hpp); either way the columns are fixed and V is the
/// Bernstein basis at the actual column positions, so V stays constant.
///
/// The faces become the named boundary sets of mesh(): "left", "right" (x1 = 0, a), "front",
/// "back" (x2 = 0, b; 3D only), "bottom" (the Bézier surface, Γ_c) and "top" (x_dim = C4).
/// Everything downstream reads mesh(); the grid indexing here is for producers and tests.
class StructuredMesh {
 public:
  /// `shape` gives the bottom surface (its extents are the body's a, b); `height` is C4.
  /// Throws InvalidInput for a resolution < 1, a grading outside [1, 10] (or != 1 with the
  /// vertical grading "contact"), a fine_depth or vertical_growth that does not fit, a growth outside [1, 2],
  /// a refinement box that does not fit or too few cells to grade, a height <= 0, or a
  /// grid with more than 2^31 − 1 unknowns (node and DOF indices are 32-bit).
  StructuredMesh(const shape::BezierShape& shape, double height, const GridResolution& resolution);

  /// The mesh this grid produces.
  const Mesh& mesh() const { return mesh_; }
  /// Moves the mesh out (the grid is then unusable).
  Mesh take_mesh() && { return std::move(mesh_); }

  int dim() const { return mesh_.dim(); }
  int num_nodes() const { return mesh_.num_nodes(); }
  int num_elements() const { return mesh_.num_elements(); }
  int num_columns() const { return num_columns_; }
  std::array<int, 3> cells() const { return cells_; }
  double height() const { return height_; }
  const shape::BezierShape& shape() const { return shape_; }
  /// Node index of column (i1, i2) in layer k.
  int node(int i1, int i2, int k) const { return i1 + (cells_[0] + 1) * i2 + num_columns_ * k; }
  /// The column lines along in-plane direction c (0: x1, 1: x2 in 3D; {0} for x2 in 2D) [m].
  const std::vector<double>& column_coordinates(int c) const { return columns_[static_cast<std::size_t>(c)]; }
  /// Vertical parameter ŝ_k of layer k.
  double layer_parameter(int k) const { return s_[static_cast<std::size_t>(k)]; }

  /// The boundary set of a face (throws InvalidInput for front/back in 2D).
  const BoundarySet& face(Face face) const { return mesh_.boundary(to_string(face)); }

 private:
  shape::BezierShape shape_;
  double height_;
  std::array<int, 3> cells_;
  int num_columns_;
  std::vector<double> s_;
  std::array<std::vector<double>, 2> columns_;
  Mesh mesh_;
};

}  // namespace frictopt::mesh
