// SPDX-License-Identifier: MIT
#include "sampled_certificate.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>
#include <random>

#include "frictopt/optim/linear_constraints.hpp"
#include "scaled_stationarity.hpp"

namespace frictopt::study::detail {

SampledCertificate sampled_certificate(ShapeOracle& oracle, const Eigen::VectorXd& alpha,
                                       const Eigen::MatrixXd& at_alpha, const LinearConstraints& upsilon,
                                       const CertifyOptions& options) {
  SampledCertificate out;
  out.computed = true;
  out.radius = options.sample_radius;
  const Eigen::Index d = alpha.size();
  out.requested = options.samples > 0 ? options.samples : static_cast<int>(10 * (d + 1));
  // Directions that keep the equalities (the volume): the null space of A_eq.
  Eigen::MatrixXd Z = Eigen::MatrixXd::Identity(d, d);
  if (upsilon.A_eq.rows() > 0) Z = Eigen::FullPivLU<Eigen::MatrixXd>(upsilon.A_eq).kernel();
  const auto k = static_cast<double>(Z.cols());
  // A fixed seed: the same run directory gives the same certificate.
  std::mt19937_64 rng(0x5eed'2026'1127ULL);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform;
  std::vector<Eigen::VectorXd> columns;
  for (Eigen::Index j = 0; j < at_alpha.cols(); ++j) columns.push_back(at_alpha.col(j));
  // No direction keeps the equalities (Υ's affine hull is the point): nothing to sample.
  for (int j = 0; Z.cols() > 0 && j < out.requested; ++j) {
    Eigen::VectorXd w(Z.cols());
    for (Eigen::Index i = 0; i < w.size(); ++i) w(i) = normal(rng);
    Eigen::VectorXd v = Z * w;
    if (!(v.norm() > 0.0)) continue;  // a draw of measure zero
    const double t = out.radius * std::pow(uniform(rng), 1.0 / k);  // uniform in the ball's volume
    v *= t / v.norm();
    // The projection onto Υ is nonexpansive and α ∈ Υ: ‖y − α‖ ≤ t.
    const optim::Projection y = optim::project_onto(upsilon, alpha + v);
    if (y.feasible_set_empty || !y.converged) {
      ++out.failed;
      continue;
    }
    try {
      const Evaluation& e = oracle.evaluate_design(y.point, true);
      if (!e.ok || !e.subgradient.allFinite()) {
        ++out.failed;
        continue;
      }
      columns.push_back(e.subgradient);
    } catch (const InvalidInput&) {  // an inverting design: skipped, as the optimizer would
      ++out.failed;
      continue;
    }
    ++out.evaluated;
    out.largest_step = std::max(out.largest_step, (y.point - alpha).norm());
  }
  Eigen::MatrixXd generators(d, static_cast<Eigen::Index>(columns.size()));
  for (std::size_t j = 0; j < columns.size(); ++j) generators.col(static_cast<Eigen::Index>(j)) = columns[j];
  out.scale = generators.colwise().norm().maxCoeff();
  out.clarke = scaled_certificate(generators, alpha, upsilon, optim::StationarityOptions{options.active_tolerance},
                                  out.scale);
  if (out.clarke.status != Status::kConverged) {
    out.message = "sampled certificate: the distance QP failed: " + out.clarke.message;
    return out;
  }
  const double scale = out.scale > 0.0 ? out.scale : 1.0;
  out.relative_distance = out.clarke.distance / scale;
  out.stationary = out.clarke.distance <= options.stationary_tolerance * out.scale;
  out.message = fmt::format("{} of {} sampled designs within {:.3e} of x evaluated (largest step {:.3e}{}); "
                            "dist(0, conv{{xi}} + N_Upsilon) over them and the {} generator(s) at x = {:.6e} "
                            "(relative {:.3e}): {}",
                            out.evaluated, out.requested, out.radius, out.largest_step,
                            out.failed ? fmt::format(", {} skipped", out.failed) : std::string(), at_alpha.cols(),
                            out.clarke.distance, out.relative_distance,
                            out.stationary ? "stationary in the sampled (Goldstein) sense at this radius"
                                           : "not stationary at this radius");
  return out;
}

}  // namespace frictopt::study::detail
