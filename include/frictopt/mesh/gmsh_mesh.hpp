// SPDX-License-Identifier: MIT
// A body brought as a Gmsh file (issue 11): a .msh mesh (format 4.1 or 2.2) or a .geo geometry
// meshed at load time, read through the Gmsh library into a mesh::Mesh whose boundary sets are
// the file's physical groups by name. One producer of a Mesh, next to the structured grid.
#pragma once

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "frictopt/mesh/mesh.hpp"

namespace frictopt::mesh {

/// How a Gmsh file becomes a mesh.
struct GmshMeshOptions {
  /// .geo only: the largest element size [m] (Gmsh's Mesh.MeshSizeMax); NaN: the sizes the
  /// .geo itself sets. A .msh is read as it is and must not be given a size.
  double size = std::numeric_limits<double>::quiet_NaN();
};

/// The body of a Gmsh file, as a Mesh of Q1 cells (quadrilaterals in 2D, hexahedra in 3D;
/// docs/meshes.md says why) with no design variables yet (V has 0 columns: the design
/// extension adds them, design_extension.hpp).
///
/// - Dimension: 3 when the file has volume elements, else 2 (then the body lies in a plane
///   z = const and x3 is dropped).
/// - Body: the elements of the physical groups of the top dimension, or all elements of that
///   dimension when the file has no such group. Nodes not used by the body are dropped; the
///   others keep the order of their Gmsh tags.
/// - Boundary sets: one per named physical group of dimension dim − 1 (an unnamed group is
///   called by its number, e.g. "3"), its facets the group's elements.
/// - A .geo is meshed by Gmsh with options.size; when its mesh has triangles or tetrahedra
///   (no Recombine / Transfinite in the .geo), it is meshed again with Gmsh's all-quad (2D)
///   or all-hex (3D) subdivision (Mesh.SubdivisionAlgorithm), which splits every simplex into
///   quads/hexes — the cells are then about half options.size.
/// - Cells with a negative Jacobian at their centre (Gmsh's orientation of a hand-written
///   .msh) are reordered; the facet orientation is not used.
///
/// Thread safety: Gmsh has one global state; every GmshMesh construction holds a process-wide
/// lock while the library is initialized and finalizes it before returning. Nothing is printed
/// (General.Terminal = 0); Gmsh's messages become the InvalidInput messages.
class GmshMesh {
 public:
  /// Throws InvalidInput naming the file for: a missing or unreadable file, an extension other
  /// than .msh/.geo, a size given for a .msh or a size that is not > 0, a Gmsh syntax error,
  /// no elements of the body's dimension, triangles/tetrahedra (in a .msh) or other unsupported
  /// or mixed element types, a 2D body that is not planar, and a boundary group with facets
  /// that are not faces of body nodes.
  GmshMesh(const std::filesystem::path& file, const GmshMeshOptions& options = {});

  const Mesh& mesh() const { return mesh_; }
  /// Moves the mesh out (this object is then unusable).
  Mesh take_mesh() && { return std::move(mesh_); }
  /// The file read.
  const std::filesystem::path& file() const { return file_; }
  /// True when a .geo's simplices were subdivided into quads/hexes.
  bool subdivided() const { return subdivided_; }
  /// Gmsh's element tag of each cell (for messages).
  const std::vector<std::size_t>& element_tags() const { return element_tags_; }

 private:
  std::filesystem::path file_;
  bool subdivided_ = false;
  std::vector<std::size_t> element_tags_;
  Mesh mesh_;
};

}  // namespace frictopt::mesh
