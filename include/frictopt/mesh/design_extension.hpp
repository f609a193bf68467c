// SPDX-License-Identifier: MIT
// The design motion of an imported body (docs/meshes.md, "The design on a patch"): a Bézier surface
// (3D) or curve (2D) over a chart of the design patch moves the patch nodes along the foundation
// normal; every other node follows an extension computed once per mesh, so that V = ∂X/∂α is
// constant and X(α) = X_ref + V α (docs/theory/problem.md §5).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "frictopt/mesh/mesh.hpp"
#include "frictopt/shape/bezier_shape.hpp"

namespace frictopt::mesh {

/// An orthonormal frame of the foundation plane: the unit normal n (pointing into the body, so
/// the foundation is {x : n·x <= offset}) and dim − 1 tangent axes e1 (, e2).
struct PlaneFrame {
  Eigen::VectorXd normal;    ///< n, size dim
  Eigen::MatrixXd tangents;  ///< dim × (dim − 1), columns e1 (, e2)
  /// The default frame: n = e_dim, tangents e1 (, e2).
  static PlaneFrame standard(int dim);
  /// The frame with normal n and, in 3D, first tangent the projection of `first_axis` onto the
  /// plane (normalized); e2 = n × e1. Throws InvalidInput when n is zero, not of size dim, or
  /// first_axis is parallel to n.
  static PlaneFrame from_normal(const Eigen::VectorXd& normal, const Eigen::VectorXd& first_axis);
  int dim() const { return static_cast<int>(normal.size()); }
  /// In-plane coordinates (e1·x, e2·x) of a point.
  Eigen::VectorXd plane_coordinates(const Eigen::Ref<const Eigen::VectorXd>& x) const;
};

/// The chart of a design patch: the bounding rectangle [origin, origin + extents] of the
/// patch's nodes in the plane coordinates of the frame; a node at plane coordinates x' has
/// Bézier parameter x' − origin in [0, a] × [0, b] (the default chart of
/// docs/meshes.md, "The design on a patch").
struct PatchChart {
  Eigen::VectorXd origin;   ///< size dim − 1 [m]
  Eigen::VectorXd extents;  ///< size dim − 1, (a[, b]) [m], each > 0
};

/// The bounding rectangle of boundary set `patch` of `body`, projected on the frame's plane.
/// Throws InvalidInput when the patch does not exist (listing the sets), or is flat in a
/// tangent direction (zero extent: a patch seen edge-on from the foundation).
PatchChart patch_chart(const Mesh& body, const std::string& patch, const PlaneFrame& frame);

/// How the nodes off the patch follow it.
enum class ExtensionKind {
  /// Scalar Laplace equation on the cells (Q1 stiffness), the normal motion of the patch as
  /// Dirichlet data, zero on the `fixed` sets, natural conditions elsewhere: smooth, for any
  /// body. One sparse Cholesky factorization, one solve per control point.
  kLaplace,
  /// The structured grid's vertical morph: a node at height t = n·x moves by
  /// basis(x' − origin)·(t_top − t)/(t_top − t_patch), t_top the body's highest and t_patch
  /// the patch's lowest height. For bodies that are a prism over the patch (the punch); it
  /// reproduces the structured grid's V when the nodes coincide.
  kSweep,
};
std::string_view to_string(ExtensionKind kind);
/// "laplace" or "sweep"; throws InvalidInput listing them.
ExtensionKind parse_extension_kind(std::string_view name);

/// Where and how the design moves an imported body.
struct DesignMotion {
  std::string patch;                ///< the boundary set that carries the Bézier surface
  PlaneFrame frame;                 ///< foundation frame (empty normal: the standard frame)
  ExtensionKind extension = ExtensionKind::kLaplace;
  /// kLaplace: boundary sets whose nodes do not move (the Dirichlet parts; the contact surface
  /// off the patch). Patch nodes on them move with the patch.
  std::vector<std::string> fixed;
};

/// The mesh `body` (any V; its V is replaced) with V from `motion` and `shape`: patch node i
/// moves by n·basis(x'_i − origin)·α; the others by the extension. `shape`'s extents must
/// equal the chart's (the case reader builds the shape from patch_chart()). Throws
/// InvalidInput for an unknown patch or fixed set, extents that differ, or a failed
/// factorization of the extension (e.g. a fixed set that covers the patch).
Mesh with_design_motion(const Mesh& body, const shape::BezierShape& shape, const DesignMotion& motion);

}  // namespace frictopt::mesh
