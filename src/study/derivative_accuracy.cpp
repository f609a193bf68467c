// SPDX-License-Identifier: MIT
#include "frictopt/study/derivative_accuracy.hpp"

#include <algorithm>

#include "frictopt/core/validation.hpp"

namespace frictopt::study {

void tighten_for_derivatives(contact::CoulombSolver::Options& coulomb, double tolerance) {
  require_field(tolerance > 0 && tolerance < 1, "tighten_for_derivatives", "tolerance", tolerance, "a value in (0, 1)");
  coulomb.relative_tolerance = std::min(coulomb.relative_tolerance, tolerance);
  coulomb.tresca.relative_tolerance = std::min(coulomb.tresca.relative_tolerance, tolerance);
  coulomb.max_iterations = std::max(coulomb.max_iterations, 200);
  coulomb.tresca.max_iterations = std::max(coulomb.tresca.max_iterations, 200000);
}

}  // namespace frictopt::study
