// SPDX-License-Identifier: MIT
// certify's sampled (Goldstein-type) certificate (internal to study; study/certificate.hpp has
// its result type and docs/theory/stationarity.md its reading).
#pragma once

#include <Eigen/Core>

#include "frictopt/core/linear_constraints.hpp"
#include "frictopt/study/certificate.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::study::detail {

/// The generators at α (`at_alpha`, d × m) together with ξ(y_j) at options.samples admissible
/// designs y_j, ‖y_j − α‖ ≤ options.sample_radius: y_j is the projection onto Υ of α + t_j v_j,
/// v_j a seeded random unit direction in the null space of Υ's equalities and t_j uniform in the
/// ball's volume (as gradient sampling draws them). Solves the oracle at each y_j: afterwards
/// the oracle's last state is no longer α's.
SampledCertificate sampled_certificate(ShapeOracle& oracle, const Eigen::VectorXd& alpha,
                                       const Eigen::MatrixXd& at_alpha, const LinearConstraints& upsilon,
                                       const CertifyOptions& options);

}  // namespace frictopt::study::detail
