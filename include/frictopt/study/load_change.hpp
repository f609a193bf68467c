// SPDX-License-Identifier: MIT
// What a design carries compared with the initial one. A cost such as target_pressure or the
// contact stress is lowered by a design that carries less load (a body pressed by a displacement
// that lifts part of its contact surface off), which is rarely the improvement the user wants;
// the run says so instead of reporting the lower Θ alone (docs/optim.md, "Outcomes").
#pragma once

#include <string>
#include <vector>

#include "frictopt/contact/contact_resultants.hpp"

namespace frictopt::study {

/// The fraction of the initial design's total normal force P⁰ by which the final design's
/// forces may differ before a run warns.
inline constexpr double kLoadChangeWarningFraction = 0.10;

/// One sentence per change of load between `initial` and `final` (empty when none): the contact
/// was lost (P⁰ > 0, P = 0); the total normal force changed by more than `fraction`·P⁰; the
/// total tangential force T (a vector in the foundation's plane) moved by more than
/// `fraction`·P⁰. Forces in N (2D: N per metre of thickness). Throws InvalidInput for a
/// fraction outside (0, 1].
[[nodiscard]] std::vector<std::string> load_change_warnings(const contact::ContactResultants& initial,
                                                            const contact::ContactResultants& final,
                                                            double fraction = kLoadChangeWarningFraction);

}  // namespace frictopt::study
