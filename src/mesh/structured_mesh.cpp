// SPDX-License-Identifier: MIT
#include "frictopt/mesh/structured_mesh.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "frictopt/core/error.hpp"
#include "frictopt/mesh/graded_coordinates.hpp"

namespace frictopt::mesh {

StructuredGridSizes structured_grid_sizes(int dim, const GridResolution& resolution) {
  const std::int64_t n1 = resolution.cells[0], n2 = dim == 3 ? resolution.cells[1] : 0, nv = resolution.cells[2];
  StructuredGridSizes sizes;
  sizes.columns = (n1 + 1) * (n2 + 1);
  sizes.nodes = sizes.columns * (nv + 1);
  sizes.elements = n1 * (dim == 3 ? n2 : 1) * nv;
  sizes.dofs = dim * sizes.nodes;
  return sizes;
}

namespace {

// Validates the resolution and height (InvalidInput naming the field) and returns the cells
// with n2 = 0 in 2D.
std::array<int, 3> validated_cells(int dim, double height, const GridResolution& resolution) {
  std::array<int, 3> cells = resolution.cells;
  if (dim == 2) cells[1] = 0;  // no x2 direction: one column row
  for (int c = 0; c < 3; ++c) {
    if (c == 1 && dim == 2) continue;
    if (cells[c] < 1)
      throw InvalidInput(fmt::format("mesh.cells[{}] = {}; expected >= 1", c == 2 && dim == 2 ? 1 : c, cells[c]));
  }
  if (!(resolution.grading >= 1.0 && resolution.grading <= 10.0))
    throw InvalidInput(fmt::format("mesh.grading = {}; expected within [1, 10]", resolution.grading));
  if (!(resolution.growth >= 1.0 && resolution.growth <= 2.0))
    throw InvalidInput(fmt::format("mesh.growth = {}; expected within [1, 2] (1 = uniform columns)", resolution.growth));
  if (resolution.refine_box && resolution.growth == 1.0)
    throw InvalidInput("mesh.refine_box is given but mesh.growth = 1 (uniform columns); expected growth in (1, 2]");
  if (!(height > 0)) throw InvalidInput(fmt::format("geometry.height = {}; expected > 0", height));
  if (resolution.vertical_grading == VerticalGrading::kContact && resolution.grading != 1.0)
    throw InvalidInput(fmt::format("mesh.grading = {} with mesh.vertical_grading = \"contact\"; expected grading only "
                                   "with vertical_grading = \"power\" (contact spaces its layers by fine_depth and "
                                   "vertical_growth)",
                                   resolution.grading));
  // Node, element and DOF indices are int: refuse a grid whose counts do not fit, before any
  // allocation (in 32-bit arithmetic the counts would wrap around).
  const StructuredGridSizes sizes = structured_grid_sizes(dim, resolution);
  constexpr std::int64_t kMaxIndex = std::numeric_limits<int>::max();
  if (sizes.dofs > kMaxIndex || sizes.elements > kMaxIndex)
    throw InvalidInput(fmt::format(
        "mesh.cells = [{}]: {} nodes, {} elements and {} unknowns; expected at most {} unknowns (32-bit indices)",
        dim == 2 ? fmt::format("{}, {}", cells[0], cells[2]) : fmt::format("{}, {}, {}", cells[0], cells[1], cells[2]),
        sizes.nodes, sizes.elements, sizes.dofs, kMaxIndex));
  return cells;
}

// Splits every grid cell into P1 simplices on the same nodes: a quadrilateral (0,1,2,3) into
// (0,1,2), (0,2,3); a hexahedron into the 6 tetrahedra of Kuhn's (Freudenthal's) triangulation
// around its diagonal 0–6, and every boundary quadrilateral (f0,f1,f2,f3) into (f0,f1,f2),
// (f0,f2,f3). Written out here rather than asked of a mesher because the grid's cells all have
// the same orientation (corner 0 lowest in every direction), and for such a grid Kuhn's split
// is conforming: the diagonal it draws on a face is the one its neighbour draws, and the one the
// boundary facets' rule draws (each face's diagonal runs from its lowest to its highest corner).
// Every tetrahedron keeps the hexahedron's orientation (det J > 0 for the box).
void split_into_simplices(int dim, Connectivity& elements, std::map<std::string, BoundarySet, std::less<>>& boundaries) {
  if (dim == 2) {
    Connectivity tri(elements.rows() * 2, 3);
    for (Eigen::Index e = 0; e < elements.rows(); ++e) {
      const auto c = elements.row(e);
      tri.row(2 * e) << c(0), c(1), c(2);
      tri.row(2 * e + 1) << c(0), c(2), c(3);
    }
    elements = std::move(tri);
    return;  // 2D facets are segments either way
  }
  static constexpr int kKuhn[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
  Connectivity tet(elements.rows() * 6, 4);
  for (Eigen::Index e = 0; e < elements.rows(); ++e)
    for (int t = 0; t < 6; ++t)
      for (int a = 0; a < 4; ++a) tet(6 * e + t, a) = elements(e, kKuhn[t][a]);
  elements = std::move(tet);
  for (auto& [name, set] : boundaries) {
    Connectivity tri(set.facets.rows() * 2, 3);
    for (Eigen::Index f = 0; f < set.facets.rows(); ++f) {
      const auto q = set.facets.row(f);
      tri.row(2 * f) << q(0), q(1), q(2);
      tri.row(2 * f + 1) << q(0), q(2), q(3);
    }
    set.facets = std::move(tri);
  }
}

}  // namespace

StructuredMesh::StructuredMesh(const shape::BezierShape& shape, double height, const GridResolution& resolution)
    : shape_(shape),
      height_(height),
      cells_(validated_cells(shape.dim(), height, resolution)),
      num_columns_(static_cast<int>(structured_grid_sizes(shape.dim(), resolution).columns)),
      mesh_(ElementKind::kQuad4, Eigen::MatrixXd::Zero(0, 2), Connectivity(), Eigen::SparseMatrix<double>(), {}) {
  const int dim = shape.dim();
  const int n1 = cells_[0], n2 = cells_[1], nv = cells_[2];
  const int num_nodes = num_columns_ * (nv + 1);
  // The layer parameters ŝ_k only decide where the layers sit; the morph stays
  // x_dim = ŝ_k·C4 + (1 − ŝ_k)·G_α(x'), linear in α for any fixed ŝ, so V stays constant.
  if (resolution.vertical_grading == VerticalGrading::kContact) {
    s_ = contact_layer_coordinates(height, nv, resolution.fine_depth, resolution.vertical_growth);
    for (double& s : s_) s /= height;
    s_.back() = 1.0;  // the top exactly (the morph's (1 − ŝ) vanishes there)
  } else {
    s_.resize(static_cast<std::size_t>(nv) + 1);
    for (int k = 0; k <= nv; ++k) s_[static_cast<std::size_t>(k)] = std::pow(static_cast<double>(k) / nv, resolution.grading);
  }

  const auto extent = shape.extents();
  // Column positions per in-plane direction: uniform (the formula of the uniform grid, so the
  // default is bit-identical), or graded toward the refinement box (docs/case-format.md,
  // "In-plane grading").
  for (int c = 0; c < dim - 1; ++c) {
    const double length = extent[static_cast<std::size_t>(c)];
    const int n = cells_[static_cast<std::size_t>(c)];
    if (resolution.growth == 1.0) {
      columns_[static_cast<std::size_t>(c)] = uniform_coordinates(length, n);
    } else {
      const double lo = resolution.refine_box ? (*resolution.refine_box)[2 * static_cast<std::size_t>(c)]
                                              : length * (1 - kDefaultRefineFraction) / 2;
      const double hi = resolution.refine_box ? (*resolution.refine_box)[2 * static_cast<std::size_t>(c) + 1]
                                              : length * (1 + kDefaultRefineFraction) / 2;
      columns_[static_cast<std::size_t>(c)] =
          graded_coordinates(length, n, lo, hi, resolution.growth, fmt::format("mesh.cells[{}]", c));
    }
  }
  if (dim == 2) columns_[1] = {0.0};
  const int d = shape.num_controls();
  Eigen::MatrixXd reference(num_nodes, dim);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(num_nodes) * static_cast<std::size_t>(d));
  for (int i2 = 0; i2 <= n2; ++i2)
    for (int i1 = 0; i1 <= n1; ++i1) {
      Eigen::VectorXd x_plane(dim - 1);
      x_plane(0) = columns_[0][static_cast<std::size_t>(i1)];
      if (dim == 3) x_plane(1) = columns_[1][static_cast<std::size_t>(i2)];
      const Eigen::VectorXd basis = shape.basis(x_plane);
      for (int k = 0; k <= nv; ++k) {
        const int n = node(i1, i2, k);
        const double s = s_[static_cast<std::size_t>(k)];
        reference.row(n).head(dim - 1) = x_plane.transpose();
        reference(n, dim - 1) = s * height;
        if (k == nv) continue;  // the top does not move: (1 − ŝ) = 0
        for (int j = 0; j < d; ++j) triplets.emplace_back(n * dim + dim - 1, j, (1.0 - s) * basis(j));
      }
    }
  Eigen::SparseMatrix<double> V(static_cast<Eigen::Index>(dim) * num_nodes, d);
  V.setFromTriplets(triplets.begin(), triplets.end());

  const int n2_cells = dim == 3 ? n2 : 1;
  Connectivity elements(static_cast<Eigen::Index>(n1) * n2_cells * nv, dim == 2 ? 4 : 8);
  Eigen::Index e = 0;
  for (int k = 0; k < nv; ++k)
    for (int i2 = 0; i2 < n2_cells; ++i2)
      for (int i1 = 0; i1 < n1; ++i1, ++e) {
        if (dim == 2) {
          elements.row(e) << node(i1, 0, k), node(i1 + 1, 0, k), node(i1 + 1, 0, k + 1), node(i1, 0, k + 1);
        } else {
          elements.row(e) << node(i1, i2, k), node(i1 + 1, i2, k), node(i1 + 1, i2 + 1, k), node(i1, i2 + 1, k),
              node(i1, i2, k + 1), node(i1 + 1, i2, k + 1), node(i1 + 1, i2 + 1, k + 1), node(i1, i2 + 1, k + 1);
        }
      }

  // The faces as named boundary sets: nodes in increasing index order, facets as before.
  std::map<std::string, BoundarySet, std::less<>> boundaries;
  for (Face face : {Face::kLeft, Face::kRight, Face::kFront, Face::kBack, Face::kBottom, Face::kTop}) {
    if (dim == 2 && (face == Face::kFront || face == Face::kBack)) continue;
    BoundarySet set;
    for (int k = 0; k <= nv; ++k)
      for (int i2 = 0; i2 <= n2; ++i2)
        for (int i1 = 0; i1 <= n1; ++i1) {
          const bool on = (face == Face::kLeft && i1 == 0) || (face == Face::kRight && i1 == n1) ||
                          (face == Face::kFront && i2 == 0) || (face == Face::kBack && i2 == n2) ||
                          (face == Face::kBottom && k == 0) || (face == Face::kTop && k == nv);
          if (on) set.nodes.push_back(node(i1, i2, k));
        }
    std::vector<std::array<int, 4>> facets;
    if (dim == 2) {
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
          facets.push_back({node(i1, i2, k), node(i1, i2 + 1, k), node(i1, i2 + 1, k + 1), node(i1, i2, k + 1)});
    } else if (face == Face::kFront || face == Face::kBack) {
      const int i2 = face == Face::kFront ? 0 : n2;
      for (int k = 0; k < nv; ++k)
        for (int i1 = 0; i1 < n1; ++i1)
          facets.push_back({node(i1, i2, k), node(i1 + 1, i2, k), node(i1 + 1, i2, k + 1), node(i1, i2, k + 1)});
    } else {
      const int k = face == Face::kBottom ? 0 : nv;
      for (int i2 = 0; i2 < n2; ++i2)
        for (int i1 = 0; i1 < n1; ++i1)
          facets.push_back({node(i1, i2, k), node(i1 + 1, i2, k), node(i1 + 1, i2 + 1, k), node(i1, i2 + 1, k)});
    }
    const int width = dim == 2 ? 2 : 4;
    set.facets.resize(static_cast<Eigen::Index>(facets.size()), width);
    for (std::size_t f = 0; f < facets.size(); ++f)
      for (int j = 0; j < width; ++j) set.facets(static_cast<Eigen::Index>(f), j) = facets[f][static_cast<std::size_t>(j)];
    boundaries.emplace(std::string(to_string(face)), std::move(set));
  }

  const bool simplices = resolution.element_family == ElementFamily::kSimplex;
  if (simplices) split_into_simplices(dim, elements, boundaries);
  const int per_cell = simplices ? (dim == 2 ? 2 : 6) : 1;
  ElementDiagnostics diagnostics;
  diagnostics.location = [n1, n2_cells, dim, per_cell](Eigen::Index element) {
    const Eigen::Index cell = element / per_cell;
    const Eigen::Index i1 = cell % n1, i2 = (cell / n1) % n2_cells, k = cell / (static_cast<Eigen::Index>(n1) * n2_cells);
    const std::string piece = per_cell > 1 ? fmt::format(", simplex {} of the cell", element % per_cell) : "";
    return dim == 3 ? fmt::format("column {},{}, layer {}{}", i1, i2, k, piece)
                    : fmt::format("column {}, layer {}{}", i1, k, piece);
  };
  diagnostics.inverted_hint = " — is a control height at or above geometry.height?";
  mesh_ = Mesh(element_kind(resolution.element_family, dim), std::move(reference), std::move(elements), std::move(V),
               std::move(boundaries), std::move(diagnostics));
}

}  // namespace frictopt::mesh
