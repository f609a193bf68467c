// SPDX-License-Identifier: MIT
// Solver settings for derivative work: difference quotients (check-gradient) and Jacobians
// (identification) are exact only if the state is far more accurate than the step they take.
#pragma once

#include "frictopt/contact/coulomb_solver.hpp"

namespace frictopt::study {

/// The relative tolerance of the state for derivative work: 1e-13 keeps the state error three
/// orders below a relative difference step of 1e-4 squared (the central-difference error).
inline constexpr double kDerivativeStateTolerance = 1e-13;

/// Tightens `coulomb` in place unless the case already asks for more: the fixed point's and
/// the inner QP's relative tolerances become min(theirs, `tolerance`), and their iteration caps
/// at least 200 and 200,000 (tighter tolerances need more iterations). `tolerance` in (0, 1).
void tighten_for_derivatives(contact::CoulombSolver::Options& coulomb, double tolerance = kDerivativeStateTolerance);

}  // namespace frictopt::study
