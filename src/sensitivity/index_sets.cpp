// SPDX-License-Identifier: MIT
#include "frictopt/sensitivity/index_sets.hpp"

#include <fmt/format.h>

#include <array>
#include <utility>

namespace frictopt::sensitivity {

std::string_view to_string(NormalSet set) {
  switch (set) {
    case NormalSet::kStrongContact: return "I+";
    case NormalSet::kNoContact: return "M";
    case NormalSet::kWeakContact: return "I0";
  }
  return "?";
}

std::string_view to_string(TangentialSet set) {
  switch (set) {
    case TangentialSet::kSectorSlip: return "K+j";
    case TangentialSet::kRaySlipVertex: return "K(ray,vertex)";
    case TangentialSet::kRaySlipEdge: return "K(j,00,j+1)";
    case TangentialSet::kSmoothSlip: return "K(smooth slip)";
    case TangentialSet::kStrongStick: return "K00";
    case TangentialSet::kWeakStickVertex: return "K0(vertex)";
    case TangentialSet::kWeakStickEdge: return "K0(edge)";
    case TangentialSet::kWeakStickSmooth: return "K0(smooth)";
    case TangentialSet::kFrictionless: return "frictionless";
    case TangentialSet::kZeroForce: return "zero force";
  }
  return "?";
}

bool NodeSets::is_weak() const {
  if (normal == NormalSet::kWeakContact) return true;
  if (normal != NormalSet::kStrongContact) return false;
  return tangential == TangentialSet::kRaySlipVertex || tangential == TangentialSet::kWeakStickVertex ||
         tangential == TangentialSet::kWeakStickEdge || tangential == TangentialSet::kWeakStickSmooth;
}

int IndexSets::count(NormalSet set) const {
  int n = 0;
  for (const NodeSets& s : nodes) n += s.normal == set;
  return n;
}

int IndexSets::count(TangentialSet set) const {
  int n = 0;
  for (const NodeSets& s : nodes) n += s.normal == NormalSet::kStrongContact && s.tangential == set;
  return n;
}

int IndexSets::num_weak_nodes() const {
  int n = 0;
  for (const NodeSets& s : nodes) n += s.is_weak();
  return n;
}

std::string IndexSets::summary() const {
  std::string tangential;
  for (TangentialSet t : {TangentialSet::kSectorSlip, TangentialSet::kRaySlipVertex, TangentialSet::kRaySlipEdge,
                          TangentialSet::kSmoothSlip, TangentialSet::kStrongStick, TangentialSet::kWeakStickVertex,
                          TangentialSet::kWeakStickEdge, TangentialSet::kWeakStickSmooth, TangentialSet::kFrictionless}) {
    const int n = count(t);
    if (n > 0) tangential += fmt::format("{}{} {}", tangential.empty() ? "" : ", ", to_string(t), n);
  }
  return fmt::format("I+ {} ({}), M {}, I0 {}; weak nodes {}", count(NormalSet::kStrongContact), tangential,
                     count(NormalSet::kNoContact), count(NormalSet::kWeakContact), num_weak_nodes());
}

IndexSets classify(const contact::ContactState& state, const contact::FrictionLaw& law) {
  using contact::FrictionFace;
  IndexSets sets;
  sets.force_tolerance = state.scales.force;
  sets.displacement_tolerance = state.scales.displacement;
  const Eigen::Index p = state.num_nodes();
  sets.nodes.resize(static_cast<std::size_t>(p));
  for (Eigen::Index i = 0; i < p; ++i) {
    NodeSets& s = sets.nodes[static_cast<std::size_t>(i)];
    const double lambda = state.lambda(i);
    if (lambda > state.scales.force)
      s.normal = NormalSet::kStrongContact;
    else if (state.normal_gap(i) > state.scales.displacement)
      s.normal = NormalSet::kNoContact;
    else
      s.normal = NormalSet::kWeakContact;
    if (s.normal != NormalSet::kStrongContact) {
      s.tangential = TangentialSet::kZeroForce;
      continue;
    }
    if (law.is_zero()) {
      s.tangential = TangentialSet::kFrictionless;
      continue;
    }
    const contact::FrictionClassification& f = state.nodes[static_cast<std::size_t>(i)].faces;
    switch (f.slip.face) {
      case FrictionFace::kVertex:
        s.tangential = TangentialSet::kSectorSlip;
        s.vertex = f.slip.index;
        break;
      case FrictionFace::kEdge:
        s.edge = f.slip.index;
        if (f.force.face == FrictionFace::kVertex) {
          s.tangential = TangentialSet::kRaySlipVertex;
          s.vertex = f.force.index;
        } else {
          s.tangential = TangentialSet::kRaySlipEdge;
        }
        break;
      case FrictionFace::kSmooth:
        s.tangential = TangentialSet::kSmoothSlip;
        break;
      case FrictionFace::kInterior:
      case FrictionFace::kDegenerate:
        switch (f.force.face) {
          case FrictionFace::kVertex:
            s.tangential = TangentialSet::kWeakStickVertex;
            s.vertex = f.force.index;
            break;
          case FrictionFace::kEdge:
            s.tangential = TangentialSet::kWeakStickEdge;
            s.edge = f.force.index;
            break;
          case FrictionFace::kSmooth: s.tangential = TangentialSet::kWeakStickSmooth; break;
          default: s.tangential = TangentialSet::kStrongStick; break;
        }
        break;
    }
  }
  return sets;
}

}  // namespace frictopt::sensitivity
