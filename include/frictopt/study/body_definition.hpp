// SPDX-License-Identifier: MIT
// Everything that defines one body and its admissible designs, in the numeric modules' types
// (io builds it from a case file; tests build it directly).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "frictopt/fem/boundary_conditions.hpp"
#include "frictopt/fem/material.hpp"
#include "frictopt/mesh/structured_mesh.hpp"
#include "frictopt/shape/admissible_set.hpp"
#include "frictopt/shape/bezier_shape.hpp"

namespace frictopt::study {

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
};

}  // namespace frictopt::study
