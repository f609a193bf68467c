// SPDX-License-Identifier: MIT
// The thesis' index sets of a Coulomb solution (docs/theory/sensitivity.md §3; thesis §4.4
// for 2D, §6.2 for the 3D n-gon),
// read off the classified contact state, for any friction law.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/contact/contact_state.hpp"
#include "frictopt/contact/friction_law.hpp"

namespace frictopt::sensitivity {

/// Normal status (docs/theory/sensitivity.md §3): I₊ strong contact (λ > τ_λ), M no contact
/// (w > τ_w), I₀ weak contact (touching without force).
enum class NormalSet { kStrongContact, kNoContact, kWeakContact };

/// Tangential status of a node with λ > τ_λ (docs/theory/sensitivity.md §3). Faces refer to the
/// friction set W of the law; indices follow contact::FaceLocation (our vertex j = thesis j+1).
enum class TangentialSet {
  kSectorSlip,       ///< K₊ⱼ (2D: K₊ at vertex 1, K₋ at vertex 0): u_t in the open sector of vertex j, q = λw_j
  kRaySlipVertex,    ///< K_{0,j,j+1} / K_{j,j+1,0}: u_t on the ray of edge j, q at one end vertex (weak)
  kRaySlipEdge,      ///< K_{j,00,j+1}: u_t on the ray of edge j, q inside the edge (strong)
  kSmoothSlip,       ///< disc/ellipse: u_t ≠ 0, q = λ·w(u_t) on the smooth boundary
  kStrongStick,      ///< K₀₀: u_t = 0, q inside λW
  kWeakStickVertex,  ///< K₀ at vertex j (2D: K₀₊ / K₀₋): u_t = 0, q = λw_j
  kWeakStickEdge,    ///< K₀ inside edge j: u_t = 0, q on the edge
  kWeakStickSmooth,  ///< disc/ellipse: u_t = 0, q on the smooth boundary
  kFrictionless,     ///< W = {0} (μ = 0): q = 0 whatever u_t
  kZeroForce         ///< λ <= τ_λ: rule R1 (docs/theory/sensitivity.md §3), no tangential status
};

std::string_view to_string(NormalSet set);
std::string_view to_string(TangentialSet set);

struct NodeSets {
  NormalSet normal = NormalSet::kNoContact;
  TangentialSet tangential = TangentialSet::kZeroForce;
  int vertex = -1;  ///< sector/force vertex j (kSectorSlip, kRaySlipVertex, kWeakStickVertex)
  int edge = -1;    ///< ray/edge j (kRaySlip*, kWeakStickEdge)
  /// Whether the node can switch pieces nearby (weak sets: K₀*, ray-at-vertex, I₀).
  bool is_weak() const;
};

/// The classification of all contact nodes with the tolerances used.
struct IndexSets {
  std::vector<NodeSets> nodes;
  double force_tolerance = 0.0;         ///< τ_λ = τ_q
  double displacement_tolerance = 0.0;  ///< τ_u = τ_w
  /// Number of nodes in each (normal, tangential) set, e.g. "I+ 12 (K+ 3, K- 0, K00 7, K0 2) M 16 I0 1".
  std::string summary() const;
  int count(NormalSet set) const;
  int count(TangentialSet set) const;
  int num_weak_nodes() const;
};

/// Reads the index sets from a classified contact state (contact::classify_nodes has run: the
/// solvers do this) with its own tolerances (state.scales, docs/theory/sensitivity.md §3); the
/// normal status uses λ_i and w_i = u_ν + g against the same scales.
IndexSets classify(const contact::ContactState& state, const contact::FrictionLaw& law);

}  // namespace frictopt::sensitivity
