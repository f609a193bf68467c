// SPDX-License-Identifier: MIT
// The optimized shape out to CAD and to other finite-element codes (docs/meshes.md, "The
// optimized shape out"): a Bézier patch as an exact STEP surface, a mesh at its designed
// positions as a Gmsh .msh (physical groups by name) or an STL of its exterior. All files are
// made by the Gmsh library (OpenCASCADE for STEP) in a child process, as every Gmsh use here
// (mesh_child_process.hpp), and returned as bytes: the caller decides where they go.
#pragma once

#include <Eigen/Core>
#include <string>

#include "frictopt/mesh/mesh.hpp"

namespace frictopt::mesh {

/// A Bézier surface (m1 × m2 control points) or curve (m2 = 1) in space [m]:
///   S(u, v) = Σ_ij B_i^{m1−1}(u) B_j^{m2−1}(v) P_{i + m1 j},  (u, v) ∈ [0, 1]².
/// A 2D body's curve lies in the plane x3 = 0.
struct BezierGeometry {
  int m1 = 0;
  int m2 = 1;
  Eigen::MatrixXd points;  ///< (m1·m2) × 3, row i + m1·j [m]
};

/// S(u, v) by de Casteljau's algorithm (stable at every degree).
Eigen::Vector3d evaluate(const BezierGeometry& geometry, double u, double v = 0.0);

/// The STEP file (ISO 10303-21, AP214 as OpenCASCADE writes it) of one Bézier surface — a
/// B-spline surface with Bézier knots, so exact — or curve, named `name`. Lengths are written in
/// millimetres, STEP's customary unit, so that CAD systems open the part at its size: a reader
/// that converts units (Gmsh's Geometry.OCCTargetUnit = "M", every CAD system) gets metres back.
/// Throws InvalidInput when the control points are not finite or Gmsh/OpenCASCADE fails.
std::string bezier_step(const BezierGeometry& geometry, const std::string& name);

/// The exterior facets of a mesh (facets of exactly one cell), oriented with the outward
/// normal (right-hand rule), one per row: 2 nodes (2D), 4 (hexahedra) or 3 (tetrahedra).
Connectivity exterior_facets(const Mesh& mesh);

enum class MeshFileFormat {
  kGmsh,  ///< MSH 4.1 (ASCII): nodes, cells, the boundary sets as named physical groups
  kStl,   ///< binary STL of the exterior surface, quadrilaterals split into two triangles (3D only)
};

/// The file of `mesh` at positions X (num_nodes × dim [m]): the cells in one physical group named
/// `volume_name`, each boundary set of the mesh in a physical group of its own name. Throws
/// InvalidInput for an STL of a 2D mesh, a position array of another size, or a Gmsh failure.
std::string mesh_file(const Mesh& mesh, const Eigen::Ref<const Eigen::MatrixXd>& X, MeshFileFormat format,
                      const std::string& volume_name);

}  // namespace frictopt::mesh
