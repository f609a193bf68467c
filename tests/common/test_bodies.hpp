// SPDX-License-Identifier: MIT
// Bodies shared by the sensitivity and study tests.
#pragma once

#include "frictopt/study/body_definition.hpp"

namespace frictopt::testing {

/// A contact definition with the solver tolerances finite differences need (state error / FD
/// step far below 1e-5).
inline study::ContactDefinition tight_contact(const contact::FrictionLaw& law) {
  study::ContactDefinition c;
  c.law = law;
  c.coulomb.relative_tolerance = 1e-14;
  c.coulomb.max_iterations = 200;
  c.coulomb.tresca.relative_tolerance = 1e-14;
  c.coulomb.tresca.max_iterations = 200000;
  return c;
}

/// The thesis' 2D body (docs/theory/examples.md §1–§2: left side clamped, top traction (−80, −50)
/// MPa, E = 1 GPa, ν = 0.3, plane strain) on an n1 × nv mesh with the admissible set of the
/// examples (C0 = 0.75, C2 = 1.9: Σα = 0.75, which the flat start α = 0.05 satisfies) and the
/// solver tolerances finite differences need (state error / FD step far below 1e-5).
inline study::BodyDefinition thesis_body_2d(const contact::FrictionLaw& law = contact::FrictionLaw::interval(0.25, 0.25),
                                            int n1 = 20, int nv = 8) {
  study::BodyDefinition b;
  b.shape = shape::BezierShape::curve(2.0, 15);
  b.height = 1.0;
  b.resolution = {{n1, 0, nv}, 1.0};
  b.material = {1e9, 0.3, fem::PlaneModel::kPlaneStrain};
  b.dirichlet = {{"left", {}, {}}};
  b.tractions = {{"top", Eigen::Vector2d(-8e7, -5e7)}};
  b.admissible.upper_bound = 0.75;
  b.admissible.height = 1.0;
  b.admissible.volume = 1.9;
  b.initial_design = Eigen::VectorXd::Constant(15, 0.05);
  b.contact = tight_contact(law);
  return b;
}

/// The 3D block of the sensitivity and study tests: 1 × 1 × 0.5 on an 8 × 8 × 4 mesh, E = 70 GPa,
/// ν = 0.33, a 3 × 3 Bézier net (C0 = 5e-3) whose initial heights make a dish-shaped bottom, and a
/// rigid plate on its top moved by `top_displacement` (default: pressed by 1.2e-3 and dragged by
/// (2e-4, 1e-4), so stick, slip and separated nodes all occur), with the solver tolerances finite
/// differences need. Tests that split the plate's motion or coarsen the mesh overwrite those fields.
inline study::BodyDefinition dish_block_3d(
    const contact::FrictionLaw& law, const Eigen::Vector3d& top_displacement = Eigen::Vector3d(2e-4, 1e-4, -1.2e-3)) {
  study::BodyDefinition b;
  b.shape = shape::BezierShape::surface(1.0, 1.0, 3, 3);
  b.height = 0.5;
  b.resolution = {{8, 8, 4}, 1.0};
  b.material = {7e10, 0.33, fem::PlaneModel::kPlaneStrain};
  b.dirichlet = {{"top", {}, top_displacement}};
  b.admissible.upper_bound = 5e-3;
  b.admissible.height = 0.5;
  b.initial_design.resize(9);
  b.initial_design << 1.4e-3, 1.0e-3, 1.5e-3, 0.9e-3, 0.4e-3, 1.1e-3, 1.6e-3, 1.2e-3, 1.7e-3;
  b.contact = tight_contact(law);
  return b;
}

/// The thesis' 2D body (20 × 8 cells) with a second traction on the right face, whose length
/// X(α) changes with the design: load cases and program steps that scale it exercise the
/// load-change term of the adjoint (load cases, histories).
inline study::BodyDefinition two_load_body_2d() {
  study::BodyDefinition b = thesis_body_2d(contact::FrictionLaw::interval(0.25, 0.25), 20, 8);
  b.tractions.push_back({"right", Eigen::Vector2d(-2e7, 0.0)});
  return b;
}

}  // namespace frictopt::testing
