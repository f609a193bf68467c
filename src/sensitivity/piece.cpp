// SPDX-License-Identifier: MIT
#include "frictopt/sensitivity/piece.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <random>
#include <set>

namespace frictopt::sensitivity {
namespace {
constexpr NodePiece kZeroForceNode{NormalBranch::kZeroForce, TangentialBranch::kZeroFriction, -1};

NodePiece contact_node(TangentialBranch t, int index = -1) { return {NormalBranch::kGapClosed, t, index}; }

int num_vertices(const contact::FrictionLaw& law) { return static_cast<int>(law.vertices().size()); }
}  // namespace

std::string Piece::summary() const {
  int gap = 0, stick = 0, vertex = 0, ray = 0, smooth = 0, zero = 0;
  for (const NodePiece& n : nodes) {
    gap += n.normal == NormalBranch::kGapClosed;
    if (n.normal != NormalBranch::kGapClosed) continue;
    stick += n.tangential == TangentialBranch::kStick;
    vertex += n.tangential == TangentialBranch::kVertexSlip;
    ray += n.tangential == TangentialBranch::kRaySlip;
    smooth += n.tangential == TangentialBranch::kSmoothSlip;
    zero += n.tangential == TangentialBranch::kZeroFriction;
  }
  return fmt::format("gap-closed {}, zero-force {}; stick {}, vertex-slip {}, ray-slip {}, smooth-slip {}, frictionless {}",
                     gap, static_cast<int>(nodes.size()) - gap, stick, vertex, ray, smooth, zero);
}

Piece default_piece(const IndexSets& sets) {
  Piece piece;
  piece.nodes.reserve(sets.nodes.size());
  for (const NodeSets& s : sets.nodes) {
    if (s.normal != NormalSet::kStrongContact) {
      piece.nodes.push_back(kZeroForceNode);  // 𝒵 = M ∪ J₂ with J₂ = I₀, rule R1
      continue;
    }
    switch (s.tangential) {
      case TangentialSet::kSectorSlip: piece.nodes.push_back(contact_node(TangentialBranch::kVertexSlip, s.vertex)); break;
      case TangentialSet::kRaySlipVertex:
      case TangentialSet::kRaySlipEdge: piece.nodes.push_back(contact_node(TangentialBranch::kRaySlip, s.edge)); break;
      case TangentialSet::kSmoothSlip: piece.nodes.push_back(contact_node(TangentialBranch::kSmoothSlip)); break;
      case TangentialSet::kFrictionless:
      case TangentialSet::kZeroForce: piece.nodes.push_back(contact_node(TangentialBranch::kZeroFriction)); break;
      default: piece.nodes.push_back(contact_node(TangentialBranch::kStick)); break;  // K₀₀ and weak stick
    }
  }
  return piece;
}

std::vector<NodePiece> node_alternatives(const NodeSets& s, const contact::FrictionLaw& law) {
  const int n = num_vertices(law);
  const bool polygon3d = law.is_polygonal() && law.dim() == 3;
  if (s.normal == NormalSet::kNoContact) return {kZeroForceNode};
  if (s.normal == NormalSet::kWeakContact) {
    // Rule R2 (docs/theory/sensitivity.md §4), generalized: no force, or contact with any
    // tangential branch.
    std::vector<NodePiece> alternatives{kZeroForceNode};
    if (law.is_zero()) {
      alternatives.push_back(contact_node(TangentialBranch::kZeroFriction));
      return alternatives;
    }
    alternatives.push_back(contact_node(TangentialBranch::kStick));
    if (law.is_polygonal())
      for (int j = 0; j < n; ++j) alternatives.push_back(contact_node(TangentialBranch::kVertexSlip, j));
    if (polygon3d)
      for (int j = 0; j < n; ++j) alternatives.push_back(contact_node(TangentialBranch::kRaySlip, j));
    return alternatives;
  }
  switch (s.tangential) {
    case TangentialSet::kWeakStickVertex: {
      // Completing the thesis' (6.1) (docs/theory/sensitivity.md §4): stick, sector slip, and (3D)
      // the rays of both adjacent edges.
      std::vector<NodePiece> alternatives{contact_node(TangentialBranch::kStick),
                                          contact_node(TangentialBranch::kVertexSlip, s.vertex)};
      if (polygon3d) {
        alternatives.push_back(contact_node(TangentialBranch::kRaySlip, (s.vertex + n - 1) % n));
        alternatives.push_back(contact_node(TangentialBranch::kRaySlip, s.vertex));
      }
      return alternatives;
    }
    case TangentialSet::kWeakStickEdge:
      return {contact_node(TangentialBranch::kStick), contact_node(TangentialBranch::kRaySlip, s.edge)};
    case TangentialSet::kRaySlipVertex:
      return {contact_node(TangentialBranch::kRaySlip, s.edge), contact_node(TangentialBranch::kVertexSlip, s.vertex)};
    case TangentialSet::kWeakStickSmooth:
      // Slip from rest on a smooth boundary has no linearizable slip piece (w(u_t) is not
      // differentiable at u_t = 0); only the stick piece is offered. Documented limitation.
      return {contact_node(TangentialBranch::kStick)};
    default: {
      IndexSets one;
      one.nodes = {s};
      return {default_piece(one).nodes.front()};
    }
  }
}

PieceEnumeration enumerate_pieces(const IndexSets& sets, const contact::FrictionLaw& law, int cap, std::uint64_t seed) {
  std::vector<std::vector<NodePiece>> alternatives;
  PieceEnumeration out;
  for (const NodeSets& s : sets.nodes) {
    alternatives.push_back(node_alternatives(s, law));
    out.cardinality *= static_cast<double>(alternatives.back().size());
  }
  if (out.cardinality <= cap) {
    // Odometer over the Cartesian product.
    std::vector<std::size_t> digit(alternatives.size(), 0);
    while (true) {
      Piece piece;
      for (std::size_t i = 0; i < alternatives.size(); ++i) piece.nodes.push_back(alternatives[i][digit[i]]);
      out.pieces.push_back(std::move(piece));
      std::size_t i = 0;
      while (i < digit.size() && ++digit[i] == alternatives[i].size()) digit[i++] = 0;
      if (i == digit.size()) break;
    }
    return out;
  }
  out.sampled = true;
  out.pieces.push_back(default_piece(sets));
  std::mt19937_64 rng{seed};
  std::set<std::vector<std::size_t>> seen;
  for (int attempt = 0; static_cast<int>(out.pieces.size()) < cap && attempt < 20 * cap; ++attempt) {
    std::vector<std::size_t> digit(alternatives.size());
    for (std::size_t i = 0; i < alternatives.size(); ++i)
      digit[i] = std::uniform_int_distribution<std::size_t>(0, alternatives[i].size() - 1)(rng);
    if (!seen.insert(digit).second) continue;
    Piece piece;
    for (std::size_t i = 0; i < alternatives.size(); ++i) piece.nodes.push_back(alternatives[i][digit[i]]);
    out.pieces.push_back(std::move(piece));
  }
  return out;
}

}  // namespace frictopt::sensitivity
