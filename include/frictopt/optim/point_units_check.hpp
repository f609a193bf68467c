// SPDX-License-Identifier: MIT
// A "converged" of BundleTrust confirmed in the per-coordinate units of the point found
// (docs/optim.md, "Confirmation in the point's units"; docs/theory/bundle-trust.md §6).
// BundleTrust::minimize/resume call it by default on stops whose units spread by more than
// Options::point_units_spread; called directly it checks any converged summary.
#pragma once

#include <Eigen/Core>

#include "frictopt/optim/bundle_trust.hpp"
#include "frictopt/optim/linear_constraints.hpp"
#include "frictopt/optim/oracle.hpp"

namespace frictopt::optim {

/// Per-coordinate units of a point: u_i = max(|x_i|, |x_ref,i|), 1 where both vanish.
[[nodiscard]] Eigen::VectorXd point_units(const Eigen::Ref<const Eigen::VectorXd>& x,
                                          const Eigen::Ref<const Eigen::VectorXd>& x_ref);

/// Spread of point_units(x, x_ref): max u_i / min u_i over the coordinates where x_i or x_ref,i
/// is nonzero (a coordinate where both vanish has no unit to compare; its u_i = 1 is a default,
/// not a measurement); 1 when fewer than two coordinates have a unit. Invariant under x → c·x.
[[nodiscard]] double point_units_spread(const Eigen::Ref<const Eigen::VectorXd>& x,
                                        const Eigen::Ref<const Eigen::VectorXd>& x_ref);

/// Υ in the variables x̃ = x ⊘ u (u_i > 0): bounds divided by u, constraint columns times u.
[[nodiscard]] LinearConstraints in_units(const LinearConstraints& constraints, const Eigen::VectorXd& u);

/// Confirms a converged `summary` of BundleTrust(options, constraints).minimize(oracle, x0):
/// BundleTrust is restarted from summary.x in the variables x̃_i = x_i/u_i, u = point_units(x,
/// x0), for one bundle's worth of iterations (2·max(n, 5)), and stops as soon as f falls by
/// more than ε·F (F = summary.value_scale). If it does not, the stop is confirmed (the better
/// of the two points is returned). If it does, x was not stationary to ε in these units: the
/// run goes on in them with the full options and its stop is confirmed in turn, at most 5
/// rounds (then kStalled, kStationarityNotCertified). options.max_iterations and
/// max_evaluations bound the totals, check included: a check that the limits cut short ends the
/// run with kMaxIterations (the stop is then not confirmed). A summary that is not converged is
/// returned unchanged. The result's x and f are in the original variables; its counters are the
/// totals; stationarity, scales, certificate, history and last_state are those of the last run,
/// in its variables (not resumable with `oracle`). options.on_iteration is not called by the
/// confirmation runs. Throws InvalidInput if x0 or summary.x has the wrong size.
[[nodiscard]] BundleTrust::Summary confirm_in_point_units(const BundleTrust::Options& options,
                                                          const LinearConstraints& constraints, Oracle& oracle,
                                                          const Eigen::Ref<const Eigen::VectorXd>& x0,
                                                          BundleTrust::Summary summary);

}  // namespace frictopt::optim
