// SPDX-License-Identifier: MIT
#include "frictopt/study/tribometer.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "frictopt/core/enum_table.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/loading_program.hpp"
#include "tribometer_readings.hpp"

namespace frictopt::study {
namespace {

using detail::kDegree;
// An automatic pull: at most this many times ramp_steps steps of the chosen length's step.
constexpr int kAutomaticRampFactor = 20;
// The press is solved to this relative accuracy in P; P(δ) is piecewise linear and increasing,
// and exactly linear (one secant step) for a flat specimen in full contact.
constexpr double kPressTolerance = 1e-10;
constexpr int kMaxPressIterations = 30;

constexpr auto kDrives = frictopt::detail::make_enum_table<TribometerDrive>(
    std::pair{TribometerDrive::kDisplacement, "displacement"}, std::pair{TribometerDrive::kForce, "force"});

}  // namespace

std::string_view to_string(TribometerDrive drive) { return kDrives.name(drive); }
TribometerDrive parse_tribometer_drive(std::string_view text) {
  return kDrives.parse(text, "experiment.drive");
}

void TribometerDefinition::validate() const {
  if (!(normal_force > 0.0 && std::isfinite(normal_force)))
    throw InvalidInput(
        fmt::format("experiment.normal_force = {}; expected a finite force > 0 N", normal_force));
  if (drive == TribometerDrive::kDisplacement && pull_displacement &&
      !(*pull_displacement > 0.0 && std::isfinite(*pull_displacement)))
    throw InvalidInput(
        fmt::format("experiment.pull_displacement = {}; expected a finite displacement > 0 m "
                    "(drive = \"displacement\"), or no value for one chosen from the law and the specimen",
                    *pull_displacement));
  if (drive == TribometerDrive::kForce && !(max_force_ratio > 0.0 && std::isfinite(max_force_ratio)))
    throw InvalidInput(fmt::format(
        "experiment.max_force_ratio = {}; expected a finite ratio Q_max/P > 0 (drive = \"force\"; "
        "above the law's largest coefficient to reach sliding in every direction)",
        max_force_ratio));
  if (drive == TribometerDrive::kForce && !(onset_tolerance > 0.0 && onset_tolerance <= 1e-2))
    throw InvalidInput(fmt::format(
        "experiment.onset_tolerance = {}; expected a relative bracket width in (0, 0.01]", onset_tolerance));
  if (angles_degrees.empty())
    throw InvalidInput("experiment.angles_degrees is empty; expected at least one pull direction");
  for (std::size_t i = 0; i < angles_degrees.size(); ++i)
    if (!std::isfinite(angles_degrees[i]))
      throw InvalidInput(fmt::format("experiment.angles_degrees[{}] = {}; expected a finite angle",
                                     i, angles_degrees[i]));
  if (ramp_steps < 1 || ramp_steps > 100000)
    throw InvalidInput(fmt::format("experiment.ramp_steps = {}; expected 1..100000", ramp_steps));
  if (angles_degrees.size() > kMaxTribometerAngles)
    throw InvalidInput(fmt::format("experiment.angles_degrees has {} angles; expected at most {} pull directions "
                                   "(docs/case-format.md, \"Size limits\")",
                                   angles_degrees.size(), kMaxTribometerAngles));
  const auto ramp_solves = static_cast<std::int64_t>(angles_degrees.size()) * ramp_steps;
  if (ramp_solves > kMaxTribometerRampSolves)
    throw InvalidInput(fmt::format("experiment.angles_degrees has {} angles with ramp_steps = {}: {} ramp solves; "
                                   "expected at most {} (fewer angles or ramp steps; docs/case-format.md, \"Size "
                                   "limits\")",
                                   angles_degrees.size(), ramp_steps, ramp_solves, kMaxTribometerRampSolves));
}

std::string Tribometer::Summary::brief_report() const {
  if (std::isnan(press_displacement))  // the force drive: no platen
    return fmt::format("tribometer: {} ({}); {} angles, {} contact solves on {} factorization{}, {:.3f} s",
                       to_string(status), message, angles.size(), contact_solves, factorizations,
                       factorizations == 1 ? "" : "s", time_seconds);
  return fmt::format(
      "tribometer: {} ({}); press δ = {:.6e} m (at most {} secant steps per load), {} angles, {} "
      "contact solves on "
      "{} factorization{}, {:.3f} s",
      to_string(status), message, press_displacement, press_iterations, angles.size(),
      contact_solves, factorizations, factorizations == 1 ? "" : "s", time_seconds) +
         (automatic_pull ? fmt::format("; pull chosen: {:.4e} m per ramp of the case's steps (3 × the elastic shear "
                                       "at sliding), ramped on to steady sliding",
                                       pull_displacement)
                         : std::string());
}

Tribometer::Tribometer(BodyDefinition body, TribometerDefinition experiment)
    : body_(std::move(body)), experiment_(std::move(experiment)) {
  experiment_.validate();
  if (body_.shape.dim() != 3)
    throw InvalidInput(
        "experiment: the tribometer needs a 3D specimen (geometry.dim = 3); a 2D body has one "
        "tangential direction and no friction polar");
  if (!body_.contact)
    throw InvalidInput("experiment: the specimen needs a [contact] table (a friction law)");
  // The platen presses along −x3 and pulls in the (x1, x2) plane: the foundation must be that
  // plane (a law turned relative to the specimen is orientation_deg, not a tilted foundation).
  if (!body_.contact->foundation.is_standard(3))
    throw InvalidInput(
        "experiment: the tribometer presses along −x3 and pulls in the (x1, x2) plane, so it needs the default "
        "foundation (no [foundation] table, or normal = [0, 0, 1], offset = 0, axis1 = [1, 0, 0]); to turn the "
        "friction law relative to the specimen use [contact.friction] orientation_deg");
}

namespace {

// The displacement drive of Tribometer::run: the specimen with a rigid platen glued to its top
// face, pressed to P by secant steps on the indentation δ and dragged by a ramped pull; counts
// its solves into the run's summary.
class PlatenDrive {
 public:
  PlatenDrive(const BodyDefinition& specimen, const TribometerDefinition& experiment, Tribometer::Summary& summary)
      : experiment_(experiment),
        summary_(summary),
        target_(experiment.normal_force),
        // a column's indentation under P: the first trial, and the first secant slope P/δ
        delta_(target_ * specimen.height / (specimen.material.young * specimen.shape.base_measure())),
        slope_(target_ / delta_),
        body_(with_platen(specimen, delta_)),
        alpha_(body_.definition().initial_design),
        builder_(body_, body_.mesh().positions(alpha_)),
        load_scale_(body_.definition().tractions.size(), 1.0),
        force_scale_(body_.definition().forces.size(), 1.0) {}

  ElasticBody& body() { return body_; }
  const StepLoadBuilder& builder() const { return builder_; }
  double indentation() const { return delta_; }
  void set_indentation(double delta) { delta_ = delta; }

  /// Finds the indentation δ at which the platen, pulled by `pull` along `angle`, carries P: each
  /// trial from `start_state` (P(δ) is piecewise linear and increasing; linear for a flat
  /// specimen in full contact, so one or two steps). False when a solve fails or P is not met.
  bool press(double pull, double angle, const Eigen::VectorXd& previous,
             std::optional<contact::ContactState> start_state, const std::string& label, BodyState& out) {
    double last_delta = 0.0, last_force = 0.0;
    bool have_last = false;
    for (int it = 1;; ++it) {
      body_.set_warm_start(start_state);  // every trial continues from the same state (a copy: the solve moves it)
      out = solve(platen(pull, angle, delta_), previous, label);
      if (out.summary.status != Status::kConverged) return false;
      const double force = out.contact->resultants.normal_force;
      summary_.press_iterations = std::max(summary_.press_iterations, it);
      if (std::abs(force - target_) <= kPressTolerance * target_) return true;
      if (it == kMaxPressIterations) {
        out.summary.status = Status::kMaxIterations;
        out.summary.message = fmt::format(
            "normal force {:.6e} N after {} secant steps on the indentation; expected {:.6e} N", force, it, target_);
        return false;
      }
      if (have_last && force != last_force && delta_ != last_delta) {
        const double secant = (force - last_force) / (delta_ - last_delta);
        if (secant > 0.0) slope_ = secant;
      }
      last_delta = delta_, last_force = force, have_last = true;
      delta_ = force > 0.0 ? delta_ + (target_ - force) / slope_ : 2.0 * delta_;  // no contact yet: press deeper
    }
  }

  /// The ramp of one angle from the pressed state: friction acts on each step's increment. A
  /// pull the case gives is ramped in ramp_steps steps; an automatic one goes on in steps of the
  /// same size until the specimen slides steadily (two consecutive sliding readings |T|/P agree
  /// to kSteadyReading). False (with the failed state and where) when a press fails.
  bool ramp(double angle_deg, double final_pull, int max_steps, const Eigen::VectorXd& pressed_tangential,
            TribometerAngleResult& r, BodyState& failed, std::string& where) {
    constexpr double kSteadyReading = 1e-7;
    const contact::FrictionLaw& law = body_.definition().contact->law;
    Eigen::VectorXd previous = pressed_tangential;
    for (int k = 1; k <= max_steps; ++k) {
      const double pull = final_pull * k / experiment_.ramp_steps;
      BodyState s;
      if (!press(pull, angle_deg * kDegree, previous, body_.warm_start(),
                 fmt::format("pull {} deg step {}", angle_deg, k), s)) {
        failed = std::move(s);
        where = fmt::format("pull at {} degrees, step {}", angle_deg, k);
        return false;
      }
      previous = builder_.tangential_displacement(s.displacement);
      const contact::ContactResultants& c = s.contact->resultants;
      r.ramp.push_back(detail::ramp_point(pull, c));
      const bool sliding = c.num_stick == 0 && c.num_slip > 0;
      if (!r.gross_sliding && sliding) {
        r.gross_sliding = true;
        r.onset_step = k - 1;
        r.onset_pull = pull;
        r.onset_force = c.tangential_force_norm;
        r.onset_normal_force = c.normal_force;
      }
      const bool steady = sliding && r.onset_step < k - 1;
      if (summary_.automatic_pull && steady) {
        // Sliding, but the friction force turns towards the pull over a few more steps: read
        // the law once two consecutive readings agree to kSteadyReading (or at the last step).
        const double previous_reading = r.measured_coefficient;
        detail::read_sliding_law(s, law, r);
        if (std::abs(r.measured_coefficient - previous_reading) <= kSteadyReading * r.measured_coefficient) break;
        if (k < max_steps) r.steady_sliding = false;  // not yet steady: this reading is provisional
        continue;
      }
      if (k == experiment_.ramp_steps && steady) detail::read_sliding_law(s, law, r);
    }
    return true;
  }

 private:
  // Every component of the top face prescribed (the same DOFs in every step).
  static std::vector<fem::FaceDirichlet> platen(double pull, double angle, double indent) {
    fem::FaceDirichlet d;
    d.boundary = "top";
    d.components = {0, 1, 2};
    d.displacement = Eigen::Vector3d(pull * std::cos(angle), pull * std::sin(angle), -indent);
    return {d};
  }
  static BodyDefinition with_platen(BodyDefinition specimen, double indent) {
    specimen.dirichlet = platen(0.0, 0.0, indent);
    return specimen;
  }
  BodyState solve(const std::vector<fem::FaceDirichlet>& dirichlet, const Eigen::VectorXd& previous,
                  const std::string& label) {
    BodyState s = body_.solve_step(alpha_, builder_.build(load_scale_, force_scale_, dirichlet, previous, true), label);
    ++summary_.contact_solves;
    if (s.summary.factorization_seconds > 0.0) ++summary_.factorizations;
    return s;
  }

  const TribometerDefinition& experiment_;
  Tribometer::Summary& summary_;
  double target_, delta_, slope_;
  ElasticBody body_;
  Eigen::VectorXd alpha_;
  StepLoadBuilder builder_;
  std::vector<double> load_scale_, force_scale_;
};

}  // namespace

Tribometer::Summary Tribometer::run(const AngleCallback& on_angle) {
  if (experiment_.drive == TribometerDrive::kForce) return run_force_ramp(on_angle);
  const auto start = std::chrono::steady_clock::now();
  Summary summary;
  const auto fail = [&](const BodyState& s, const std::string& what) {
    summary.status = s.summary.status;
    summary.message = fmt::format("{}: {}", what, s.summary.message);
    summary.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return summary;
  };
  PlatenDrive drive(body_, experiment_, summary);

  // 1. Press to P from the unloaded body.
  BodyState pressed;
  const Eigen::VectorXd no_slip = Eigen::VectorXd::Zero(2 * drive.body().contact_boundary()->num_nodes());
  if (!drive.press(0.0, 0.0, no_slip, std::nullopt, "press", pressed)) return fail(pressed, "press");
  summary.press_displacement = drive.indentation();
  const double pressed_delta = drive.indentation();
  const std::optional<contact::ContactState> pressed_contact = drive.body().warm_start();
  const Eigen::VectorXd pressed_tangential = drive.builder().tangential_displacement(pressed.displacement);

  // 2. Per angle: ramp the pull from the pressed state.
  summary.automatic_pull = !experiment_.pull_displacement;
  const double final_pull = summary.automatic_pull ? automatic_pull_displacement(body_, experiment_.normal_force)
                                                   : *experiment_.pull_displacement;
  summary.pull_displacement = final_pull;
  const int max_steps = summary.automatic_pull ? kAutomaticRampFactor * experiment_.ramp_steps : experiment_.ramp_steps;
  for (double angle_deg : experiment_.angles_degrees) {
    TribometerAngleResult r;
    r.angle_degrees = angle_deg;
    drive.body().set_warm_start(pressed_contact);
    drive.set_indentation(pressed_delta);
    BodyState failed;
    std::string where;
    if (!drive.ramp(angle_deg, final_pull, max_steps, pressed_tangential, r, failed, where)) return fail(failed, where);
    if (on_angle) on_angle(r);
    summary.angles.push_back(std::move(r));
  }
  summary.status = Status::kConverged;
  int sliding = 0, steady = 0;
  for (const auto& a : summary.angles) sliding += a.gross_sliding, steady += a.steady_sliding;
  summary.message = fmt::format("gross sliding reached at {} of {} angles, steady sliding at the end of the ramp at {}",
                                sliding, summary.angles.size(), steady);
  summary.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

double Tribometer::automatic_pull_displacement(const BodyDefinition& specimen, double normal_force) {
  if (!specimen.contact) throw InvalidInput("experiment: the specimen needs a [contact] table");
  const contact::FrictionLaw& law = specimen.contact->law;
  double mu_max = 0.0;
  for (int k = 0; k < 360; ++k) {
    const double theta = k * kDegree;
    mu_max = std::max(mu_max, law.support(Eigen::Vector2d(std::cos(theta), std::sin(theta))));
  }
  const double young = specimen.material.young, poisson = specimen.material.poisson;
  const double shear_modulus = young / (2.0 * (1.0 + poisson));
  const double shear_at_sliding = mu_max * normal_force * specimen.height / (shear_modulus * specimen.shape.base_measure());
  return 3.0 * shear_at_sliding;
}

}  // namespace frictopt::study
