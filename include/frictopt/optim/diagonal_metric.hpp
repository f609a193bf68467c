// SPDX-License-Identifier: MIT
// A safeguarded diagonal variable metric for the proximal term of BundleTrust's direction QP
// (docs/optim.md, "Variable metric").
#pragma once

#include <Eigen/Core>

namespace frictopt::optim {

/// The diagonal metric H = diag(h) of the proximal term dᵀHd/(2t) and the secant pairs it was
/// estimated from. h is relative (geometric mean 1), so t keeps its units (x²/f); empty h is
/// the identity (the Euclidean method).
struct DiagonalMetric {
  Eigen::VectorXd h;            ///< diagonal of H, geometric mean 1; empty = identity
  Eigen::MatrixXd steps;        ///< s_j = x_{k+1} − x_k of the last serious steps, newest last (n × m)
  Eigen::MatrixXd differences;  ///< u_j = g(x_{k+1}) − g(x_k), same columns as `steps`
  int updates = 0;              ///< pairs accepted since the last reset
  int resets = 0;               ///< resets to the identity
  [[nodiscard]] bool is_identity() const { return h.size() == 0; }
};

/// Least-squares diagonal secant estimate of a Hessian from pairs (s_j, u_j):
/// b_i = Σ_j s_ij u_ij / Σ_j s_ij² (minimizes Σ_j ‖diag(b) s_j − u_j‖²; Karmitsa's diagonal
/// bundle method). Coordinates that did not move (Σ_j s_ij² <= 1e-12·max) or whose curvature
/// reads <= 0 (a kink or nonconvexity between the points) take `previous` (1 if it is empty);
/// the result is normalized to geometric mean 1 and clamped to [κ^{-1/2}, κ^{1/2}], κ =
/// `ratio_bound` >= 1, so that max h / min h <= κ. Returns an empty vector when no coordinate
/// gives an estimate. Invariant under x_i → c_i x_i (h_i → h_i/c_i², before the clamp) and f → c f.
[[nodiscard]] Eigen::VectorXd diagonal_secant_estimate(const Eigen::MatrixXd& steps,
                                                       const Eigen::MatrixXd& differences,
                                                       const Eigen::VectorXd& previous, double ratio_bound);

/// Adds the pair (s, u) of a serious step (keeping the last `memory` pairs), estimates h from
/// the stored pairs (diagonal_secant_estimate from the identity) and moves the metric towards it
/// geometrically: h := h_old^{1−w}·h_est^w, w = `damping` in (0, 1] (h_old = 1 for the
/// identity; 1 = no damping). A pair with sᵀu <= 0 (no positive curvature along the step:
/// BFGS's safeguard) or a non-finite entry is not used; returns whether h was updated. Throws
/// InvalidInput on size mismatch, memory < 1, damping outside (0, 1] or ratio_bound < 1.
bool update_diagonal_metric(DiagonalMetric& metric, const Eigen::VectorXd& s, const Eigen::VectorXd& u,
                            int memory, double ratio_bound, double damping = 1.0);

/// Back to the identity: h and the pairs are dropped (the model misbehaved, BundleTrust).
void reset_diagonal_metric(DiagonalMetric& metric);

}  // namespace frictopt::optim
