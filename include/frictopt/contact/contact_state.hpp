// SPDX-License-Identifier: MIT
// Per-node results of a contact solve in the dual variables of docs/theory/state-problem.md §5:
// forces z_i = (q_i, λ_i), the gradient pieces (−u_t^i, u_ν^i + g_i) = (Mz + c)_i, the node status
// (separated / stick / slip) and, for slip, the active face of the friction set — the data the
// sensitivity analysis reads (docs/theory/sensitivity.md §3).
#pragma once

#include <Eigen/Core>
#include <span>
#include <string_view>
#include <vector>

#include "frictopt/contact/friction_law.hpp"

namespace frictopt::contact {

/// Mechanical status of a contact node.
enum class NodeStatus {
  kSeparated,  ///< λ_i <= τ_λ: no normal force (gap open, or touching without force: M ∪ I₀)
  kStick,      ///< λ_i > τ_λ and |u_t^i| <= τ_u
  kSlip        ///< λ_i > τ_λ and |u_t^i| > τ_u
};
/// "separated", "stick", "slip".
std::string_view to_string(NodeStatus status);
/// Inverse of to_string; throws InvalidInput listing the accepted spellings.
NodeStatus parse_node_status(std::string_view text);

/// Classification of one node.
struct NodeClassification {
  NodeStatus status = NodeStatus::kSeparated;
  /// Faces from FrictionLaw::classify: `force` is where q_i lies in s_i·W (interior = strong
  /// stick, edge/vertex/smooth = at the slip limit); `slip` is the face exposed by u_t^i
  /// (vertex j = sector S_j, edge j = ray ρ_j; kInterior when not slipping).
  FrictionClassification faces;
  /// u_t^i/|u_t^i| for slipping nodes (the disc/ellipse "direction"); zero otherwise.
  Eigen::Vector2d slip_direction = Eigen::Vector2d::Zero();
};

/// Absolute tolerances used by classify_nodes, derived from the solution (see there).
struct ClassificationScales {
  double force = 0.0;  ///< τ_λ = τ_q = ε_cl·Λ
  double displacement = 0.0;  ///< τ_u = τ_w = ε_cl·U
};

/// Dimensionless residuals of a contact solution (definitions in docs/contact.md):
/// with Λ = max(‖z‖_∞, tiny) and U = max(‖∇‖_∞, ‖c‖_∞, tiny), ∇ = Mz + c,
///   kkt_residual        = max_i ‖z_i − P_i(z_i − (Λ/U)∇_i)‖ / Λ   (natural map, P_i onto
///                         {λ >= 0} × s_i·W, blocks in the Euclidean norm);
///   complementarity_gap = max_i (λ_i|w_i| + |s_i N_W(u_t^i) − ⟨q_i, u_t^i⟩|) / (Λ·U),
///                         w_i = u_ν^i + g_i = ∇_λ, u_t^i = −∇_q.
/// Both vanish exactly at a solution; they do not use the solver's step length or norms.
struct ContactResiduals {
  double kkt_residual = 0.0;
  double complementarity_gap = 0.0;
};

/// The state of p contact nodes in dimension dim ∈ {2, 3}.
/// Layout (docs/theory/state-problem.md §3, node-interleaved):
/// z = (q_1, λ_1, q_2, λ_2, …), q_i ∈ R^{dim−1}.
struct ContactState {
  int dim = 3;
  /// Forces z (size dim·p): q_i = −τ_i (friction resistance), λ_i >= 0 normal force.
  Eigen::VectorXd z;
  /// ∇ = Mz + c (size dim·p) per node: (−u_t^i, u_ν^i + g_i), from a fresh operator apply.
  Eigen::VectorXd gradient;
  /// Slip bounds s_i used by the last solve (Coulomb: s = λ at the fixed point).
  Eigen::VectorXd slip_bound;
  /// Per-node classification, filled by the solvers (classify_nodes).
  std::vector<NodeClassification> nodes;
  /// The tolerances the classification used.
  ClassificationScales scales;

  ContactState() = default;
  /// Zero forces for p nodes (a cold start).
  ContactState(int dimension, Eigen::Index num_nodes);

  Eigen::Index num_nodes() const { return z.size() / dim; }
  /// λ_i.
  double lambda(Eigen::Index i) const { return z(dim * i + dim - 1); }
  /// q_i (2D: component 1 is 0).
  Eigen::Vector2d q(Eigen::Index i) const;
  /// u_t^i = −∇_q (2D: component 1 is 0).
  Eigen::Vector2d u_t(Eigen::Index i) const;
  /// w_i = u_ν^i + g_i = ∇_λ (gap after deformation).
  double normal_gap(Eigen::Index i) const { return gradient(dim * i + dim - 1); }
  /// Vector of all λ_i (size p).
  Eigen::VectorXd normal_forces() const;
  /// Whether the classification says node i is stick / slip / separated.
  bool is_stick(Eigen::Index i) const { return nodes.at(static_cast<std::size_t>(i)).status == NodeStatus::kStick; }
  bool is_slip(Eigen::Index i) const { return nodes.at(static_cast<std::size_t>(i)).status == NodeStatus::kSlip; }
  bool is_separated(Eigen::Index i) const { return nodes.at(static_cast<std::size_t>(i)).status == NodeStatus::kSeparated; }
};

/// Classifies every node of `state` (z, gradient, slip_bound must be set) into
/// separated/stick/slip and friction faces, following docs/theory/sensitivity.md §3: with
/// Λ = max(max_i λ_i, max_i |q_i|, tiny) and U = max(max_i |u_t^i|, max_i |w_i|, c_scale, tiny)
/// (c_scale = ‖c‖_∞ carries the gaps g and the free elastic response, so a state where every
/// node sticks with closed gaps still has a displacement scale),
/// τ_λ = τ_q = ε_cl·Λ and τ_u = ε_cl·U; the slip-ray angle tolerance is max(ε_cl, τ_u/|u_t^i|)
/// (the direction uncertainty an absolute error τ_u in u_t induces). ε_cl must exceed the
/// solver's relative KKT residual. `laws` has 1 (shared) or p entries.
void classify_nodes(ContactState& state, std::span<const FrictionLaw> laws,
                    double relative_tolerance, double c_scale);

/// The residuals of ContactResiduals for forces z, gradient ∇ = Mz + c and slip bounds s.
/// `c_scale` = ‖c‖_∞. `laws` has 1 (shared) or p entries.
ContactResiduals contact_residuals(std::span<const FrictionLaw> laws,
                                   const Eigen::Ref<const Eigen::VectorXd>& slip_bound,
                                   const Eigen::Ref<const Eigen::VectorXd>& z,
                                   const Eigen::Ref<const Eigen::VectorXd>& gradient, int dim,
                                   double c_scale);

}  // namespace frictopt::contact
