// SPDX-License-Identifier: MIT
// The benchmarks' 3D punch (bench/study, bench/experiments, bench/mesh): one definition.
#pragma once

#include <Eigen/Core>

#include "frictopt/contact/friction_law.hpp"
#include "frictopt/study/body_definition.hpp"

namespace frictopt::bench {

// The punch of cases3d/punch with an n × n × n/2 grid: a plate presses the top down and
// sideways, a dish-shaped 4 × 4 Bézier bottom, isotropic 16-gon friction μ = 0.3.
inline frictopt::study::BodyDefinition punch(int n, int layers) {
  using namespace frictopt;
  study::BodyDefinition b;
  b.shape = shape::BezierShape::surface(1.0, 1.0, 4, 4);
  b.height = 0.5;
  b.resolution = {{n, n, layers}, 1.5};
  b.material = {7e10, 0.33, fem::PlaneModel::kPlaneStrain};
  b.dirichlet = {{"top", {}, Eigen::Vector3d(1e-4, 0.0, -1.2e-3)}};
  b.admissible.upper_bound = 5e-3;
  b.admissible.height = 0.5;
  b.initial_design.resize(16);
  b.initial_design << 1.5e-3, 1.0e-3, 1.0e-3, 1.5e-3, 1.0e-3, 0.5e-3, 0.5e-3, 1.0e-3, 1.0e-3, 0.5e-3, 0.5e-3, 1.0e-3,
      1.5e-3, 1.0e-3, 1.0e-3, 1.5e-3;
  study::ContactDefinition c;
  c.law = contact::FrictionLaw::regular_polygon(0.3, 16);
  b.contact = c;
  return b;
}

}  // namespace frictopt::bench
