// SPDX-License-Identifier: MIT
// The kinds of cells a Mesh can hold, and the facts about them that do not need the element's
// shape functions (those live in the element classes: q1_element.hpp, p1_element.hpp).
#pragma once

#include <string_view>

namespace frictopt::mesh {

/// Cell kinds. A new element adds an enumerator here, a class with shape functions and a
/// quadrature rule (like Q1Element, P1Element), and one line in the dispatch of elements.hpp
/// (docs/architecture.md, "A new element").
enum class ElementKind {
  kQuad4,  ///< bilinear quadrilateral (2D Q1)
  kHex8,   ///< trilinear hexahedron (3D Q1)
  kTri3,   ///< linear triangle (2D P1)
  kTet4,   ///< linear tetrahedron (3D P1)
};

/// The two families a body can be meshed with: tensor-product cells (Q1: quadrilaterals,
/// hexahedra) or simplices (P1: triangles, tetrahedra). A case chooses the family
/// (`[mesh] element`), the dimension chooses the kind.
enum class ElementFamily { kTensorProduct, kSimplex };

std::string_view to_string(ElementKind kind);
/// Inverse of to_string; throws InvalidInput listing the accepted names.
ElementKind parse_element_kind(std::string_view name);

constexpr bool is_simplex(ElementKind kind) { return kind == ElementKind::kTri3 || kind == ElementKind::kTet4; }
constexpr ElementFamily family_of(ElementKind kind) {
  return is_simplex(kind) ? ElementFamily::kSimplex : ElementFamily::kTensorProduct;
}
constexpr int spatial_dimension(ElementKind kind) {
  return kind == ElementKind::kQuad4 || kind == ElementKind::kTri3 ? 2 : 3;
}
/// The kind of `family` in `dim` dimensions (dim 2 or 3).
constexpr ElementKind element_kind(ElementFamily family, int dim) {
  if (family == ElementFamily::kSimplex) return dim == 2 ? ElementKind::kTri3 : ElementKind::kTet4;
  return dim == 2 ? ElementKind::kQuad4 : ElementKind::kHex8;
}
constexpr int nodes_per_element(ElementKind kind) {
  switch (kind) {
    case ElementKind::kQuad4: return 4;
    case ElementKind::kHex8: return 8;
    case ElementKind::kTri3: return 3;
    case ElementKind::kTet4: return 4;
  }
  return 0;
}
/// Nodes of one boundary facet (segment: 2, triangle: 3, quadrilateral: 4).
constexpr int nodes_per_facet(ElementKind kind) {
  switch (kind) {
    case ElementKind::kQuad4:
    case ElementKind::kTri3: return 2;
    case ElementKind::kHex8: return 4;
    case ElementKind::kTet4: return 3;
  }
  return 0;
}
/// VTK cell type: 9 (VTK_QUAD), 12 (VTK_HEXAHEDRON), 5 (VTK_TRIANGLE) or 10 (VTK_TETRA).
constexpr int vtk_cell_type(ElementKind kind) {
  switch (kind) {
    case ElementKind::kQuad4: return 9;
    case ElementKind::kHex8: return 12;
    case ElementKind::kTri3: return 5;
    case ElementKind::kTet4: return 10;
  }
  return 0;
}

}  // namespace frictopt::mesh
