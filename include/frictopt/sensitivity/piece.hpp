// SPDX-License-Identifier: MIT
// Pieces of the piecewise smooth solution map: per contact node, which branch of the contact
// and friction law is imposed as an equation (docs/theory/sensitivity.md §4–§5), their
// default choice (the thesis' §5.2 and its 3D analogue) and the enumeration of the set 𝕃.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "frictopt/sensitivity/index_sets.hpp"

namespace frictopt::sensitivity {

/// The equation imposed in the normal direction: gap closed (u_ν + g = 0, λ free: 𝒞 = I₊ ∪ J₁)
/// or zero force (λ = 0: 𝒵 = M ∪ J₂).
enum class NormalBranch { kGapClosed, kZeroForce };

/// The equations imposed in the tangential direction(s):
///  kStick       u_t = 0 (γ, γ₁),
///  kVertexSlip  q = λ w_j, u_t free (β; 2D: vertex 1 = slip +, vertex 0 = slip −),
///  kRaySlip     q on the line of edge j and u_t locked to the edge's normal ray (γ₂, 3D),
///  kSmoothSlip  q = λ w(u_t) for a disc/ellipse (u_t ≠ 0),
///  kZeroFriction q = 0 (rule R1 for zero-force nodes, and frictionless laws).
enum class TangentialBranch { kStick, kVertexSlip, kRaySlip, kSmoothSlip, kZeroFriction };

struct NodePiece {
  NormalBranch normal = NormalBranch::kZeroForce;
  TangentialBranch tangential = TangentialBranch::kZeroFriction;
  int index = -1;  ///< vertex (kVertexSlip) or edge (kRaySlip) index
  bool operator==(const NodePiece&) const = default;
};

/// One piece: a NodePiece per contact node.
struct Piece {
  std::vector<NodePiece> nodes;
  /// Short description, e.g. "gap 12, zero-force 17; stick 9, vertex-slip 3".
  std::string summary() const;
};

/// The thesis' choice (§5.2; docs/theory/sensitivity.md §4): weak stick → stick, weak contact →
/// zero force, ray slip with the force at a vertex → ray slip. Valid at every point.
Piece default_piece(const IndexSets& sets);

/// The node-level alternatives of one node (docs/theory/sensitivity.md §4: the
/// thesis' (4.1)–(4.3) and (6.1)–(6.4), completed, and rule R2): a single entry for strict nodes.
std::vector<NodePiece> node_alternatives(const NodeSets& node, const contact::FrictionLaw& law);

/// The pieces 𝕃 through the current point: the Cartesian product of node_alternatives.
struct PieceEnumeration {
  std::vector<Piece> pieces;
  double cardinality = 1.0;  ///< |𝕃| (may exceed what was enumerated)
  bool sampled = false;      ///< true when |𝕃| > cap and `pieces` holds a seeded random sample
};
/// Enumerates 𝕃; when |𝕃| > cap, returns the default piece plus cap−1 distinct random pieces
/// drawn with std::mt19937_64(seed) (the thesis met |𝕃| = 59049).
PieceEnumeration enumerate_pieces(const IndexSets& sets, const contact::FrictionLaw& law, int cap = 256,
                                  std::uint64_t seed = 20261121);

}  // namespace frictopt::sensitivity
