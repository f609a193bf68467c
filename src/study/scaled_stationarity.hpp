// SPDX-License-Identifier: MIT
// The stationarity QP of optim::stationarity_certificate on subgradients divided by their scale
// (internal to study: certify's exact and sampled certificates share it).
#pragma once

#include <Eigen/Core>

#include "frictopt/optim/stationarity.hpp"

namespace frictopt::study::detail {

// N_Υ is a cone, so dist(0, conv{ξ_i/s} + N) = dist(0, conv{ξ_i} + N)/s; the dense QP's
// tolerances are absolute, and ξ of a cost in N² (e.g. 1e14) against unit constraint normals
// would leave it stuck at its start.
inline optim::StationarityCertificate scaled_certificate(const Eigen::MatrixXd& Xi, const Eigen::VectorXd& x,
                                                         const optim::LinearConstraints& constraints,
                                                         const optim::StationarityOptions& options, double scale) {
  const double s = scale > 0.0 ? scale : 1.0;
  optim::StationarityCertificate c = optim::stationarity_certificate(Xi / s, x, constraints, options);
  c.distance *= s;
  c.subgradient_part *= s;
  c.normal_part *= s;
  c.subgradient_scale *= s;
  return c;
}

}  // namespace frictopt::study::detail
