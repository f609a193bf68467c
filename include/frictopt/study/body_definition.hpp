// SPDX-License-Identifier: MIT
// Everything that defines one body and its admissible designs, in the numeric modules' types
// (io builds it from a case file; tests build it directly).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/fem/boundary_conditions.hpp"
#include "frictopt/fem/material.hpp"
#include "frictopt/mesh/structured_mesh.hpp"
#include "frictopt/shape/admissible_set.hpp"
#include "frictopt/shape/bezier_shape.hpp"

namespace frictopt::study {

/// Unilateral contact with Coulomb friction on Γ_c against the foundation x_dim <= 0.
struct ContactDefinition {
  /// The friction law at every contact node (2D: an interval law; 3D: disc, polygon, ellipse).
  contact::FrictionLaw law = contact::FrictionLaw::disc(0.0);
  contact::CoulombSolver::Options coulomb;
  /// Largest number of contact unknowns m = dim·p for which M = G A⁻¹ Gᵀ is formed densely
  /// (m³/3 flops from the Schur factor, then m² per product); above it M is applied through
  /// the Schur factor L (two triangular solves, 2m² per product, no m³ work). The contact
  /// DOFs are always ordered last in the factorization so that L comes with it.
  int dense_delassus_max_unknowns = 1500;
};

/// The cost functional of a study (spec 05 §2.4; cost module).
struct CostDefinition {
  enum class Kind { kTargetPressure, kNormalForcePower, kCompliance, kPressureNorm, kTotalSlip };
  Kind kind = Kind::kCompliance;
  /// kTargetPressure: uniform target pressure p̄ [Pa], λ̄_i = p̄·a_i; NaN: the initial total
  /// normal force spread as a uniform pressure (spec 05 §2.3's reading of the thesis' target).
  double target_pressure = std::numeric_limits<double>::quiet_NaN();
  double exponent = 4.0;    ///< kNormalForcePower (thesis: 4), kPressureNorm
  double smoothing = 1e-6;  ///< kTotalSlip [m]
};

struct BodyDefinition {
  std::string name = "body";                 ///< used in output file names
  shape::BezierShape shape = shape::BezierShape::curve(1.0, 2);
  double height = 1.0;                       ///< C4 [m]
  mesh::GridResolution resolution;
  fem::IsotropicMaterial material;
  std::vector<fem::FaceDirichlet> dirichlet;  ///< Γ_u
  std::vector<fem::FaceTraction> tractions;   ///< Γ_p
  shape::AdmissibleSetParameters admissible;  ///< Υ
  Eigen::VectorXd initial_design;             ///< α⁰
  std::optional<ContactDefinition> contact;   ///< absent: no foundation (pure elasticity)
};

}  // namespace frictopt::study
