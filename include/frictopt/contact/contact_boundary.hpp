// SPDX-License-Identifier: MIT
// The potential contact nodes Γ_c of a finite element body and the maps between the dual
// contact variables z and the FE degrees of freedom (docs/theory/state-problem.md §1, §3, §5).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string_view>
#include <vector>

#include "frictopt/fem/boundary_conditions.hpp"
#include "frictopt/mesh/design_extension.hpp"
#include "frictopt/mesh/mesh.hpp"

namespace frictopt::contact {

/// The rigid foundation (docs/theory/friction-frame.md §3): the plane n·x = d with the body on the
/// side n·x >= d (n the unit normal pointing into the body), and the frame of the friction law in
/// that plane: first axis t1, in 3D t2 = n × t1 (mesh::PlaneFrame). The default (an empty
/// frame) is n = e_dim, t1 = e1 (, t2 = e2), d = 0: the thesis' foundation x_dim <= 0.
struct Foundation {
  mesh::PlaneFrame frame;  ///< empty normal: the standard frame of the body's dimension
  double offset = 0.0;     ///< d [m]
  /// True for the thesis' foundation (standard frame and d = 0) of dimension dim.
  bool is_standard(int dim) const;
};

/// Contact nodes are the nodes of the mesh's contact surface (a named boundary set; "bottom", the
/// Bézier surface, for the structured grid) whose DOFs are all free: a node of Γ_c on Γ_u is not
/// a contact node (docs/theory/problem.md §3). The frame is the foundation's (Foundation):
/// tangential components along t1 (, t2), normal along n into the body; by default the global
/// axes x1 (, x2) and x_dim upward (docs/architecture.md, docs/theory/friction-frame.md §3).
///
/// The dual variable z has per-node blocks z_i = (q_i, λ_i) (dim−1 tangential, then normal),
/// where q_i = −τ_i is the friction resistance and λ_i ≥ 0 the normal force. The operator
/// G (dim·p × n_free) has rows −T_i (tangential) and N_i (normal), so the contact forces on the
/// body are Gᵀz = Nᵀλ + Tᵀτ and G u = (−u_t, u_ν) per node: per node the rows −t1ᵀ (, −t2ᵀ), nᵀ
/// on the node's dim DOFs (frame_rows(); standard foundation: diag(−1, (−1,) 1)).
///
/// Lifetime: keeps no reference; built from the mesh and DOF map once.
class ContactBoundary {
 public:
  /// `surface` names the boundary set of `mesh` that is Γ_c (throws InvalidInput if absent).
  /// `foundation`: the plane and frame (InvalidInput unless the frame has the mesh's dimension
  /// and d is finite).
  ContactBoundary(const mesh::Mesh& mesh, const fem::DofMap& dofs, std::string_view surface = kDefaultSurface,
                  Foundation foundation = {});
  /// The contact surface's name in meshes of the structured grid (its Bézier bottom).
  static constexpr std::string_view kDefaultSurface = "bottom";

  int dim() const { return dim_; }
  Eigen::Index num_nodes() const { return static_cast<Eigen::Index>(nodes_.size()); }
  Eigen::Index num_unknowns() const { return dim_ * num_nodes(); }
  /// Number of free FE DOFs (columns of G).
  Eigen::Index num_free() const { return num_free_; }
  /// Mesh node index of contact node i.
  const std::vector<int>& nodes() const { return nodes_; }
  /// The foundation (its frame filled in: the standard one when it was given empty).
  const Foundation& foundation() const { return foundation_; }
  /// True for the thesis' foundation x_dim >= 0 (G's rows are ±unit rows on single DOFs).
  bool standard_foundation() const { return standard_; }
  /// F (dim × dim): rows −t1ᵀ (, −t2ᵀ), nᵀ, so that (G v)_i = F v_node and the contact force on
  /// node i in global axes is Fᵀ z_i. Orthogonal up to the signs of its rows.
  const Eigen::MatrixXd& frame_rows() const { return rows_; }
  /// In-plane coordinates x' of the contact nodes (p × dim−1); constant in α.
  const Eigen::MatrixXd& plane_coordinates() const { return plane_; }
  /// Projected (x'-plane) area of Γ_c attributed to each contact node [m²; 2D: m per metre of
  /// thickness]: a quarter (3D) or half (2D) of each adjacent bottom facet. Projected onto the
  /// foundation plane, so the pressure at node i is λ_i / area_i. Constant in α. A facet that is a
  /// parallelogram in the plane (the structured grid's) gives each node a quarter; any other
  /// quadrilateral (imported meshes) gives node a the integral of its shape function N_a over the
  /// projected facet; a triangle (tetrahedral meshes) gives each of its nodes a third (∫ N_a, all
  /// positive: the linear triangle has no vanishing vertex weights).
  const Eigen::VectorXd& tributary_areas() const { return areas_; }
  /// Initial gaps g_i = n·X(node_i) − d (docs/theory/problem.md §3: G_α(x'_i) = X(node_i, dim−1)
  /// for the standard foundation).
  Eigen::VectorXd gaps(const Eigen::Ref<const Eigen::MatrixXd>& X) const;
  /// The constant gap matrix B̃ = ∂g/∂α (p × d): the rows of the mesh's V at the contact nodes'
  /// normal components. For the structured grid these are the Bézier basis at the nodes (the
  /// bottom layer has ŝ = 0), bit for bit BezierShape::gap_matrix(plane_coordinates()); for an
  /// imported body they are the patch's motion (zero off the patch;
  /// docs/meshes.md, "The design on a patch").
  Eigen::MatrixXd gap_jacobian(const mesh::Mesh& mesh) const;

  /// w_free += Gᵀ z.
  void add_transpose_times(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> w_free) const;
  /// G v for a free-DOF vector v: per node (−v_t, v_ν).
  Eigen::VectorXd times(const Eigen::Ref<const Eigen::VectorXd>& v_free) const;
  /// The same from a full DOF vector (num_dofs).
  Eigen::VectorXd times_full(const Eigen::Ref<const Eigen::VectorXd>& v_full) const;
  /// u_t of every contact node from a full DOF vector: (t_k·u_node)_k, node-interleaved
  /// ((dim−1)·p; the standard foundation: the node's x1 (, x2) components).
  Eigen::VectorXd tangential_displacements(const Eigen::Ref<const Eigen::VectorXd>& u_full) const;
  /// G as a sparse matrix (dim·p × n_free).
  Eigen::SparseMatrix<double> matrix() const;
  /// Free-DOF index of contact node i, component c.
  int free_dof(Eigen::Index i, int c) const { return free_dofs_[static_cast<std::size_t>(dim_ * i + c)]; }

 private:
  int dim_;
  Eigen::Index num_free_;
  std::vector<int> nodes_;
  Foundation foundation_;
  bool standard_ = true;
  Eigen::MatrixXd rows_;  // F
  std::vector<int> free_dofs_;  // per contact unknown, node-major
  Eigen::MatrixXd plane_;
  Eigen::VectorXd areas_;
};

}  // namespace frictopt::contact
