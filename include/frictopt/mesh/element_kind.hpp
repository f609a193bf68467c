// SPDX-License-Identifier: MIT
// The kinds of cells a Mesh can hold, and the facts about them that do not need the element's
// shape functions (those live in the element classes, e.g. q1_element.hpp).
#pragma once

#include <string_view>

namespace frictopt::mesh {

/// Cell kinds. A new element adds an enumerator here, a class with shape functions and a Gauss
/// rule (like Q1Element), and one line in each dispatch (docs/architecture.md).
enum class ElementKind {
  kQuad4,  ///< bilinear quadrilateral (2D Q1)
  kHex8,   ///< trilinear hexahedron (3D Q1)
};

std::string_view to_string(ElementKind kind);
/// Inverse of to_string; throws InvalidInput listing the accepted names.
ElementKind parse_element_kind(std::string_view name);

constexpr int spatial_dimension(ElementKind kind) { return kind == ElementKind::kQuad4 ? 2 : 3; }
constexpr int nodes_per_element(ElementKind kind) { return kind == ElementKind::kQuad4 ? 4 : 8; }
/// Nodes of one boundary facet (segment: 2, quadrilateral: 4).
constexpr int nodes_per_facet(ElementKind kind) { return kind == ElementKind::kQuad4 ? 2 : 4; }
/// VTK cell type: 9 (VTK_QUAD) or 12 (VTK_HEXAHEDRON).
constexpr int vtk_cell_type(ElementKind kind) { return kind == ElementKind::kQuad4 ? 9 : 12; }

}  // namespace frictopt::mesh
