// SPDX-License-Identifier: MIT
// The tribometer tests' specimen: a flat aluminium block 0.1 × 0.1 × 0.05 m, 6 × 6 × 3 cells,
// E = 70 GPa, ν = 0.33, pressed by its top (the experiment replaces or drops that platen).
#pragma once

#include "frictopt/study/body_definition.hpp"
#include "study/contact_validation.hpp"

namespace frictopt::study::testing {

inline BodyDefinition tribometer_specimen(const contact::FrictionLaw& law) {
  validation::BlockSpec s;
  s.width = 0.1;
  s.height = 0.05;
  s.cells = 6;
  s.layers = 3;
  s.young = 7e10;
  s.poisson = 0.33;
  s.law = law;
  s.top_displacement = Eigen::Vector3d(0.0, 0.0, -1e-6);
  BodyDefinition def = validation::block_definition(s);
  def.initial_design.setZero();  // flat bottom
  return def;
}

}  // namespace frictopt::study::testing
