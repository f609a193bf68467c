// SPDX-License-Identifier: MIT
// From a runtime ElementKind to the element class that implements it: the one place where the
// element types are listed (fem's kernels and Mesh's geometry are templates over the class).
#pragma once

#include <utility>

#include "frictopt/mesh/element_kind.hpp"
#include "frictopt/mesh/p1_element.hpp"
#include "frictopt/mesh/q1_element.hpp"

namespace frictopt::mesh {

/// Calls f(Element{}) with the element class of `kind` and returns its result. Every element
/// class provides kDim, kKind, kNodes, Point, corners(), values(), gradients(), centre(),
/// scaled_jacobian_at_corner(), quadrature() and a Facet type with kNodes, kPoints and shape()
/// (see Q1Element, P1Element).
template <class F>
decltype(auto) with_element(ElementKind kind, F&& f) {
  switch (kind) {
    case ElementKind::kQuad4: return std::forward<F>(f)(Q1Element<2>{});
    case ElementKind::kTri3: return std::forward<F>(f)(P1Element<2>{});
    case ElementKind::kTet4: return std::forward<F>(f)(P1Element<3>{});
    case ElementKind::kHex8: break;
  }
  return std::forward<F>(f)(Q1Element<3>{});
}

}  // namespace frictopt::mesh
