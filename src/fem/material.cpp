// SPDX-License-Identifier: MIT
#include "frictopt/fem/material.hpp"

#include <fmt/format.h>

#include <string>

#include "frictopt/core/error.hpp"

namespace frictopt::fem {

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
