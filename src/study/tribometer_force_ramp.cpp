// SPDX-License-Identifier: MIT
// The force-driven tribometer (TribometerDrive::kForce; docs/experiments.md §4): the specimen
// floats — its [[dirichlet]] tables are dropped, so every rigid-body mode is held by contact and
// friction alone (docs/experiments.md §5, the floating-body solver) — and its top face carries the
// normal force P and a tangential force Q e_θ as uniform tractions. Q is ramped from 0 in
// ramp_steps increments, friction acting on each step's slip increment
// (docs/theory/loading-program.md).
//
// Why force control answers a different question than the platen: under a prescribed pull the
// specimen always has an equilibrium and the force saturates at the law's capacity; under a
// prescribed force there is NO static equilibrium beyond the capacity μ(θ)·P (the radial
// function of W in the force direction θ), so the onset of gross sliding is the end of the
// existence of equilibria. The ramp brackets it (last equilibrium, first step without one); a
// bisection then refines it to `onset_tolerance`, every trial started from the last ramp
// equilibrium so that the slip increment is the one of a single load step. The limit
// equilibrium found there is the state in which the whole contact is about to slide: its
// friction force is the point of W in direction θ, and its slip direction must lie in the normal
// cone of W there (the normality rule) — both are reported.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "frictopt/core/error.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/loading_program.hpp"
#include "frictopt/study/tribometer.hpp"
#include "tribometer_readings.hpp"

namespace frictopt::study {
namespace {

// Bisection steps: the bracket halves per step, so 60 reach any tolerance >= 1e-18·Q_max.
constexpr int kMaxBisections = 60;
using detail::kDegree;
using detail::ramp_point;

}  // namespace

// The specimen of the force drive. Tractions: the case's own, then the press (index n) and the
// pull split into its x1 and x2 parts (indices n + 1, n + 2; scales Q cos θ / Q_max and
// Q sin θ / Q_max), so that every angle and every ramp step shares one body and one
// factorization: the stiffness does not depend on the loads.
namespace {
BodyDefinition force_driven_specimen(BodyDefinition definition, double P, double q_max) {
  const double top_area = definition.shape.base_measure();
  definition.dirichlet.clear();  // floating: contact and friction hold every rigid mode
  const auto top_traction = [&](const Eigen::Vector3d& t) {
    fem::FaceTraction traction;
    traction.boundary = "top";
    traction.traction = t;
    return traction;
  };
  definition.tractions.push_back(top_traction(Eigen::Vector3d(0.0, 0.0, -P / top_area)));
  definition.tractions.push_back(top_traction(Eigen::Vector3d(q_max / top_area, 0.0, 0.0)));
  definition.tractions.push_back(top_traction(Eigen::Vector3d(0.0, q_max / top_area, 0.0)));
  return definition;
}
}  // namespace

Tribometer::Summary Tribometer::run_force_ramp(const AngleCallback& on_angle) {
  const auto start = std::chrono::steady_clock::now();
  Summary summary;
  const double P = experiment_.normal_force;
  const double q_max = experiment_.max_force_ratio * P;

  const BodyDefinition definition = force_driven_specimen(body_, P, q_max);
  const std::size_t pull_x = body_.tractions.size() + 1, pull_y = body_.tractions.size() + 2;

  const Eigen::VectorXd alpha = definition.initial_design;
  const std::vector<double> force_scale(definition.forces.size(), 1.0);
  const auto fail = [&](const BodyState& s, const std::string& what) {
    summary.status = s.summary.status;
    summary.message = fmt::format("{}: {}", what, s.summary.message);
    summary.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return summary;
  };
  ElasticBody body(definition);
  if (body.num_floating_modes() == 0)
    throw InvalidInput(
        "experiment: drive = \"force\" needs a specimen whose tangential rigid motions are held by friction "
        "alone, but its [[constraint]] tables hold them; remove them or use drive = \"displacement\"");
  const StepLoadBuilder builder(body, body.mesh().positions(alpha));
  std::vector<double> load_scale(definition.tractions.size(), 1.0);
  const Eigen::Index p = body.contact_boundary()->num_nodes();
  const contact::FrictionLaw& law = definition.contact->law;
  // A trial without equilibrium: the capacity report (a priori from the net load: beyond μ(θ)·P)
  // or the floating solver's "no equilibrium" (its residual stalls; at the capacity itself the
  // equilibrium exists only in the limit). Other failures (iteration caps) end the run.
  const auto no_equilibrium = [](const BodyState& s) {
    return s.contact && s.contact->floating && s.contact->floating->status == Status::kDiverged;
  };

  std::optional<BodyState> pressed;
  summary.press_displacement = std::nan("");  // no platen: the press is a traction
  for (double angle_deg : experiment_.angles_degrees) {
    const Eigen::Vector2d direction(std::cos(angle_deg * kDegree), std::sin(angle_deg * kDegree));
    const auto solve = [&](double fraction, const Eigen::VectorXd& previous,
                           const std::optional<contact::ContactState>& warm, const std::string& label) {
      load_scale[pull_x] = fraction * direction(0);
      load_scale[pull_y] = fraction * direction(1);
      body.set_warm_start(warm);
      BodyState s = body.solve_step(alpha, builder.build(load_scale, force_scale, definition.dirichlet, previous, true),
                                    label);
      ++summary.contact_solves;
      if (s.summary.factorization_seconds > 0.0) ++summary.factorizations;
      return s;
    };

    TribometerAngleResult r;
    r.angle_degrees = angle_deg;
    // 1. Every angle starts from the pressed state (P, no pull), solved once from the unloaded body.
    if (!pressed) {
      pressed = solve(0.0, Eigen::VectorXd::Zero(2 * p), std::nullopt, "press");
      if (pressed->summary.status != Status::kConverged) return fail(*pressed, "press");
    }
    BodyState last = *pressed;
    double last_fraction = 0.0;
    // 2. Ramp Q until the first step without equilibrium.
    for (int k = 1; k <= experiment_.ramp_steps && !r.gross_sliding; ++k) {
      const double fraction = static_cast<double>(k) / experiment_.ramp_steps;
      const Eigen::VectorXd previous = builder.tangential_displacement(last.displacement);
      BodyState s = solve(fraction, previous, last.contact->state, fmt::format("pull {} deg step {}", angle_deg, k));
      if (no_equilibrium(s)) {
        r.gross_sliding = true;
        r.onset_step = k - 1;
        // 3. Bisection between the last equilibrium and this step, each trial from the last
        //    equilibrium (one load step: the slip increment is that of the final step).
        const std::optional<contact::ContactState> base_state = last.contact->state;
        double lo = last_fraction, hi = fraction;
        BodyState limit = last;
        for (int it = 0; it < kMaxBisections && hi - lo > experiment_.onset_tolerance * hi; ++it) {
          const double mid = 0.5 * (lo + hi);
          BodyState t = solve(mid, previous, base_state, fmt::format("onset {} deg bisection {}", angle_deg, it + 1));
          if (t.summary.status == Status::kConverged) {
            lo = mid;
            limit = std::move(t);
          } else if (no_equilibrium(t)) {
            hi = mid;
          } else {
            return fail(t, fmt::format("onset bisection at {} degrees, Q = {:.9e} N", angle_deg, mid * q_max));
          }
        }
        const contact::ContactResultants& c = limit.contact->resultants;
        r.ramp.push_back(ramp_point(lo * q_max, c));
        r.onset_force = c.tangential_force_norm;
        r.onset_normal_force = c.normal_force;
        if (lo > 0.0) detail::read_sliding_law(limit, law, r);  // the limit equilibrium
        break;
      }
      if (s.summary.status != Status::kConverged)
        return fail(s, fmt::format("pull at {} degrees, step {} (Q = {:.6e} N)", angle_deg, k, fraction * q_max));
      r.ramp.push_back(ramp_point(fraction * q_max, s.contact->resultants));
      last = std::move(s);
      last_fraction = fraction;
    }
    if (on_angle) on_angle(r);
    summary.angles.push_back(std::move(r));
  }
  summary.status = Status::kConverged;
  int sliding = 0;
  for (const auto& a : summary.angles) sliding += a.gross_sliding;
  summary.message = fmt::format(
      "force drive: the pull force exceeded the friction capacity (no static equilibrium) at {} of {} angles; "
      "onset bracketed to {:.0e} relative",
      sliding, summary.angles.size(), experiment_.onset_tolerance);
  summary.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace frictopt::study
