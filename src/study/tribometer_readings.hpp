// SPDX-License-Identifier: MIT
// What the tribometer reads off a solved state (both drives, tribometer.cpp and
// tribometer_force_ramp.cpp): a ramp point, and the friction law as the measured forces show it —
// |T|/P against the radial function μ(φ) of W, the λ-weighted slip direction ŝ and the
// normality residual |N_W(ŝ) − ⟨ŝ, −T/P⟩| / N_W(ŝ) (docs/experiments.md §4).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <numbers>

#include "frictopt/contact/friction_law.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/tribometer.hpp"

namespace frictopt::study::detail {

inline constexpr double kDegree = std::numbers::pi / 180.0;

inline double angle_degrees(const Eigen::Vector2d& v) { return std::atan2(v(1), v(0)) / kDegree; }

inline TribometerRampPoint ramp_point(double pull, const contact::ContactResultants& c) {
  TribometerRampPoint point;
  point.pull = pull;
  point.normal_force = c.normal_force;
  point.tangential_force = c.tangential_force;
  point.stick_fraction = c.contact_area > 0.0 ? c.stick_area / c.contact_area : 0.0;
  point.num_stick = c.num_stick;
  point.num_slip = c.num_slip;
  return point;
}

/// Fills the `sliding_*`, angle, coefficient and normality fields of `r` from state `s` and sets
/// r.steady_sliding. The slip fields stay NaN when no node slips.
inline void read_sliding_law(const BodyState& s, const contact::FrictionLaw& law, TribometerAngleResult& r) {
  const contact::ContactResultants& c = s.contact->resultants;
  const contact::ContactState& state = s.contact->state;
  r.steady_sliding = true;
  r.sliding_force = c.tangential_force_norm;
  r.sliding_normal_force = c.normal_force;
  const Eigen::Vector2d resistance = -c.tangential_force / c.normal_force;  // Σq/P ∈ W: along the pull
  r.force_angle_degrees = angle_degrees(resistance);
  r.measured_coefficient = resistance.norm();
  // μ(φ) = the radial function of W in the force direction: the largest t with t·d ∈ W.
  r.law_coefficient = law.max_step(Eigen::Vector2d::Zero(), 1.0, resistance.normalized());
  r.coefficient_error = std::abs(r.measured_coefficient - r.law_coefficient) / r.law_coefficient;
  Eigen::Vector2d slip = Eigen::Vector2d::Zero();
  for (Eigen::Index i = 0; i < state.num_nodes(); ++i)
    if (state.is_slip(i)) slip += state.lambda(i) * state.nodes[static_cast<std::size_t>(i)].slip_direction;
  if (slip.norm() == 0.0) return;
  slip.normalize();
  r.slip_angle_degrees = angle_degrees(slip);
  r.sliding_resistance = slip.dot(resistance);
  r.law_resistance = law.support(slip);
  r.normality_residual = std::abs(r.law_resistance - r.sliding_resistance) / r.law_resistance;
}

}  // namespace frictopt::study::detail
