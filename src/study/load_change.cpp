// SPDX-License-Identifier: MIT
#include "frictopt/study/load_change.hpp"

#include <fmt/format.h>

#include <cmath>

#include "frictopt/core/error.hpp"

namespace frictopt::study {

std::vector<std::string> load_change_warnings(const contact::ContactResultants& initial,
                                              const contact::ContactResultants& final, double fraction) {
  if (!(fraction > 0.0 && fraction <= 1.0))
    throw InvalidInput(fmt::format("load_change_warnings: fraction = {}; expected in (0, 1]", fraction));
  std::vector<std::string> warnings;
  const double p0 = initial.normal_force;
  const double p = final.normal_force;
  // Without an initial load there is nothing to compare with (a body that starts separated).
  if (!(p0 > 0.0) || !std::isfinite(p)) return warnings;
  const char* unit = initial.dim == 2 ? "N/m" : "N";
  const char* area_unit = initial.dim == 2 ? "m" : "m²";
  if (!(p > 0.0)) {
    warnings.push_back(fmt::format("the final design has lost contact: total normal force {:.4g} {} at the initial "
                                   "design, 0 at the final one",
                                   p0, unit));
    return warnings;
  }
  const double change = (p - p0) / p0;
  if (std::abs(change) > fraction)
    warnings.push_back(fmt::format("the final design carries a different load: total normal force {:.4g} {} (initial "
                                   "{:.4g} {}, {:+.1f} %; warned beyond ±{:.0f} %), contact area {:.4g} {} (initial "
                                   "{:.4g} {}); Θ of the two designs is not compared at the same load: prescribe the "
                                   "load by a force to compare it",
                                   p, unit, p0, unit, 100.0 * change, 100.0 * fraction, final.contact_area,
                                   area_unit, initial.contact_area, area_unit));
  const double tangential_change = (final.tangential_force - initial.tangential_force).norm();
  if (tangential_change > fraction * p0)
    warnings.push_back(fmt::format("the final design carries a different tangential load: |T| = {:.4g} {} (initial "
                                   "{:.4g} {}), a change of {:.4g} {} = {:.1f} % of the initial normal force",
                                   final.tangential_force_norm, unit, initial.tangential_force_norm, unit,
                                   tangential_change, unit, 100.0 * tangential_change / p0));
  return warnings;
}

}  // namespace frictopt::study
