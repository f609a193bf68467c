// SPDX-License-Identifier: MIT
// `frictopt export-shape RUN_DIR` and Python's frictopt.export_shape (docs/meshes.md, "The
// optimized shape out"): a run's design as CAD and as a mesh for other finite-element codes.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "frictopt/mesh/cad_export.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::io {

/// The design patch of a body at design x (α, or (α, s) with friction orientation as a design)
/// as the exact Bézier surface (3D) or curve (2D) in space. The patch's reference nodes lie in
/// the plane n·X = t₀ of the chart's frame (n, tangents, origin c, extents a, b), and patch node
/// X moves by G(x') n (docs/theory/problem.md; thesis §3.1), so by the linear precision of
/// Bernstein polynomials
///   S(u, v) = Σ_ij B_i(u) B_j(v) P_ij,   P_ij = T (c + (a i/(m1−1), b j/(m2−1))) + (t₀ + α_ij) n
/// is the designed patch exactly, (u, v) = ((x'₁ − c₁)/a, (x'₂ − c₂)/b).
struct DesignSurface {
  /// Absent when the patch is not plane in its reference (a curved face: the motion along one
  /// normal is then not a Bézier surface in space); `note` says so.
  std::optional<mesh::BezierGeometry> geometry;
  /// max over the patch nodes of |S(u_i, v_i) − X_i(α)| [m]: the surface checked against the mesh.
  double max_node_deviation = 0.0;
  /// The patch's size (its chart's diagonal) [m], the scale of max_node_deviation.
  double size = 0.0;
  std::string note;
};
/// `positions` is the body's mesh at x (mesh().positions(α)), which the caller has computed.
[[nodiscard]] DesignSurface design_surface(const study::ElasticBody& body, const Eigen::Ref<const Eigen::VectorXd>& x,
                                           const Eigen::Ref<const Eigen::MatrixXd>& positions);

/// What export_shape wrote.
struct ShapeExport {
  std::vector<std::filesystem::path> files;  ///< in the run directory
  DesignSurface surface;
  std::vector<std::string> notes;            ///< what was not written, and why
};

/// Writes into the run directory, named after the case's output.name N: N_design.step (the
/// design patch, design_surface; not for a curved patch), N_optimized.msh (the body at the design:
/// cells, boundary sets as named physical groups) and, in 3D, N_optimized.stl (its exterior). The
/// design is the run's final_design.json, or `design_file` (a design JSON) when given. The run's
/// case.toml must still define the run's problem (its fingerprint is checked, as certify does).
/// Files are written as every run file is (RunDirectory: atomically, never over a file that is
/// not ours). Throws InvalidInput naming the file and what is wrong.
ShapeExport export_shape(const std::filesystem::path& run_dir, const std::filesystem::path& design_file = {});

}  // namespace frictopt::io
