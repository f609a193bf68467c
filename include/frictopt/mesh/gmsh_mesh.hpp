// SPDX-License-Identifier: MIT
// A body brought as a Gmsh file (docs/meshes.md): a .msh mesh (format 4.1 or 2.2) or a .geo
// geometry meshed at load time, read through the Gmsh library into a mesh::Mesh whose boundary sets
// are the file's physical groups by name. One producer of a Mesh, next to the structured grid.
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "frictopt/mesh/mesh.hpp"

namespace frictopt::mesh {

/// The process-wide default of GmshMeshOptions::trust_geo (false until set; the command line
/// sets it for --trust-geo, the Python module for load_case(..., trust_geo=True)).
bool trust_geo_by_default();
void set_trust_geo_by_default(bool trust);

/// How a Gmsh file becomes a mesh.
struct GmshMeshOptions {
  /// .geo only: the largest element size [m] (Gmsh's Mesh.MeshSizeMax); NaN: the sizes the
  /// .geo itself sets. A .msh is read as it is and must not be given a size.
  double size = std::numeric_limits<double>::quiet_NaN();
  /// .geo only: run the file with every Gmsh command, unscanned (the user vouches for it; the
  /// command line's --trust-geo). False: the file and its Includes must pass check_geo_file.
  bool trust_geo = trust_geo_by_default();
  /// The folder a .geo's Include/Merge may name files in (with its sub-folders); empty: the
  /// .geo's own folder. The case reader passes the case file's folder.
  std::filesystem::path allowed_root{};
  /// The most unknowns (nodes × dim) the mesh may have; a larger mesh is refused when Gmsh
  /// has made or read it, before anything is assembled (docs/case-format.md, "Size limits").
  std::int64_t max_unknowns = 2'000'000;
  /// The unknowns the Gmsh child's memory is sized for (> 0, at most max_unknowns); 0: as
  /// max_unknowns. The case reader passes the unknowns whose solve fits the memory limit
  /// (study::max_unknowns_within_memory), so a .geo asking for far more cells ends within
  /// seconds in the child's allocation failure, not after minutes of meshing.
  std::int64_t budget_unknowns = 0;
  /// Wall-clock seconds the Gmsh child process may take (reading, meshing); then it is killed
  /// and the file refused.
  double time_limit_seconds = 600.0;
  /// The cells the body is meshed with (docs/meshes.md): kTensorProduct, Q1 quadrilaterals or
  /// hexahedra (a .geo's simplices are subdivided by Gmsh, a .msh's by frictopt), or kSimplex,
  /// P1 triangles or tetrahedra as Gmsh makes them or the .msh holds them (no subdivision; a
  /// file with quadrilaterals or hexahedra is then refused).
  ElementFamily family = ElementFamily::kTensorProduct;
};

/// Refuses a .geo file that could do more than describe a geometry: throws InvalidInput naming
/// file:line and the command for System, SystemCall, NonBlockingSystemCall, Shell, OnelabRun,
/// Exit, Abort, Save, Print, Sleep, Plugin, SetNumber/SetString, file-writing Printf (`> "f"`,
/// `>> "f"`), options outside Geometry.* and Mesh.*, an Include/Merge/ShapeFromFile whose
/// argument is not one string literal, names a file outside `allowed_root` or a file of another
/// kind (Merge: .msh, .geo, .step/.stp, .brep, .iges/.igs), an unterminated string or comment,
/// and Includes nested deeper than 16. Included and merged .geo files are checked the same way.
/// Returns every file the .geo reads (itself first), for the run's fingerprint.
std::vector<std::filesystem::path> check_geo_file(const std::filesystem::path& file,
                                                  const std::filesystem::path& allowed_root);

/// The memory this process may still use [bytes]: the machine's MemAvailable (/proc/meminfo),
/// or less under a cgroup limit (memory.max − memory.current); 0 when neither can be read.
std::uint64_t available_memory_bytes();

/// Checks an ASCII .msh file (formats 2.2 and 4.1) line by line before Gmsh reads it: the
/// $MeshFormat header, the counts of $Nodes and $Elements, the number of entries on every node
/// and element line (an element line must hold exactly its type's nodes), and that every
/// element names a node the file defines. Throws InvalidInput naming file:line. A binary .msh
/// is only checked for its header (Gmsh then reads it in the child process).
void check_msh_file(const std::filesystem::path& file);

/// The body of a Gmsh file, as a Mesh of Q1 cells (quadrilaterals in 2D, hexahedra in 3D;
/// docs/meshes.md says why) or, with options.family = kSimplex, of P1 cells (triangles,
/// tetrahedra), with no design variables yet (V has 0 columns: the design extension adds
/// them, design_extension.hpp).
///
/// - Dimension: 3 when the file has volume elements, else 2 (then the body lies in a plane
///   z = const and x3 is dropped).
/// - Body: the elements of the physical groups of the top dimension, or all elements of that
///   dimension when the file has no such group. Nodes not used by the body are dropped; the
///   others keep the order of their Gmsh tags.
/// - Boundary sets: one per named physical group of dimension dim − 1 (an unnamed group is
///   called by its number, e.g. "3"), its facets the group's elements.
/// - A .geo is meshed by Gmsh with options.size; for Q1 cells, when its mesh has triangles or tetrahedra
///   (no Recombine / Transfinite in the .geo), it is meshed again with Gmsh's all-quad (2D)
///   or all-hex (3D) subdivision (Mesh.SubdivisionAlgorithm), which splits every simplex into
///   quads/hexes — the cells are then about half options.size.
/// - Cells with a negative Jacobian at their centre (Gmsh's orientation of a hand-written
///   .msh) are reordered; the facet orientation is not used.
///
/// Gmsh runs in a child process (fork): a crash, an Exit or a hang inside Gmsh ends the child,
/// never the caller, and becomes an InvalidInput naming the file; the child is killed after
/// options.time_limit_seconds and its address space is bounded by the memory available. The
/// mesh comes back through a pipe. Before the child starts, a .msh passes check_msh_file and
/// (unless options.trust_geo) a .geo passes check_geo_file. Nothing is printed; Gmsh's
/// messages become the InvalidInput messages.
class GmshMesh {
 public:
  /// Throws InvalidInput naming the file for: a missing or unreadable file, an extension other
  /// than .msh/.geo, a size given for a .msh or a size that is not > 0, a Gmsh syntax error,
  /// no elements of the body's dimension, other unsupported
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
  /// Every file the mesh was made from (the .msh, or the .geo and the files it includes and
  /// merges), for the run's fingerprint; a trusted .geo lists only itself.
  const std::vector<std::filesystem::path>& source_files() const { return source_files_; }

 private:
  std::filesystem::path file_;
  bool subdivided_ = false;
  std::vector<std::size_t> element_tags_;
  std::vector<std::filesystem::path> source_files_;
  Mesh mesh_;
};

}  // namespace frictopt::mesh
