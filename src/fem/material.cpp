// SPDX-License-Identifier: MIT
#include "frictopt/fem/material.hpp"

#include <fmt/format.h>

#include <string>

#include "frictopt/core/error.hpp"

namespace frictopt::fem {

std::string_view to_string(PlaneModel model) {
  return model == PlaneModel::kPlaneStrain ? "plane_strain" : "plane_stress";
}

PlaneModel parse_plane_model(std::string_view name) {
  if (name == "plane_strain") return PlaneModel::kPlaneStrain;
  if (name == "plane_stress") return PlaneModel::kPlaneStress;
  throw InvalidInput(fmt::format("material.model = '{}'; expected plane_strain or plane_stress", name));
}

void IsotropicMaterial::validate() const {
  if (!(young > 0)) throw InvalidInput(fmt::format("material.young = {}; expected > 0", young));
  if (!(poisson >= 0 && poisson < 0.5))
    throw InvalidInput(fmt::format("material.poisson = {}; expected 0 <= poisson < 0.5", poisson));
}

double IsotropicMaterial::lame_lambda(int dim) const {
  const double lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  if (dim == 2 && plane_model == PlaneModel::kPlaneStress) {
    const double mu = shear_modulus();
    return 2.0 * lambda * mu / (lambda + 2.0 * mu);
  }
  return lambda;
}

}  // namespace frictopt::fem
