// SPDX-License-Identifier: MIT
// Bernstein polynomials on [0, 1]: the basis of the Bézier curve and surface
// (docs/theory/problem.md §2).
#pragma once

#include <Eigen/Core>

namespace frictopt::shape {

/// All degree+1 Bernstein polynomials of the given degree at t ∈ [0, 1]:
/// b_i(t) = C(degree, i) t^i (1 − t)^(degree − i), i = 0..degree (docs/theory/problem.md §2; the
/// thesis' β_{i+1}^{d} with d = degree + 1). Evaluated by de Casteljau's recurrence, which is
/// stable for all t ∈ [0, 1]. Requires degree >= 0.
Eigen::VectorXd bernstein_basis(int degree, double t);

/// d/dt of bernstein_basis: degree·(b^{degree−1}_{i−1}(t) − b^{degree−1}_i(t))
/// (docs/theory/problem.md §6); zero vector for degree 0.
Eigen::VectorXd bernstein_basis_derivative(int degree, double t);

}  // namespace frictopt::shape
