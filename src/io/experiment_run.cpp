// SPDX-License-Identifier: MIT
#include "frictopt/io/experiment_run.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "frictopt/core/error.hpp"
#include "frictopt/io/csv_writer.hpp"
#include "frictopt/io/summary_json.hpp"

namespace frictopt::io {

std::string describe_angle(const study::TribometerAngleResult& a, study::TribometerDrive drive) {
  const bool force_drive = drive == study::TribometerDrive::kForce;
  if (a.steady_sliding && force_drive)
    return fmt::format(
        "θ = {:7.2f}°: no static equilibrium beyond Q = {:.9e} N (ramp step {}); limit state: |T|/P = {:.9f}, law "
        "radial μ(φ) = {:.9f} (rel. error {:.1e}), force at φ = {:.3f}°, slip at {:.3f}°, normality {:.1e}, stick "
        "fraction {:.3f}",
        a.angle_degrees, a.onset_force, a.onset_step + 1, a.measured_coefficient, a.law_coefficient,
        a.coefficient_error, a.force_angle_degrees, a.slip_angle_degrees, a.normality_residual,
        a.ramp.back().stick_fraction);
  if (a.steady_sliding)
    return fmt::format(
        "θ = {:7.2f}°: sliding from step {} (|T| = {:.4e} N); sliding: |T|/P = {:.9f}, law radial μ(φ) = {:.9f} "
        "(rel. error {:.1e}), force at φ = {:.3f}°, slip at {:.3f}°, normality {:.1e}",
        a.angle_degrees, a.onset_step + 1, a.onset_force, a.measured_coefficient, a.law_coefficient,
        a.coefficient_error, a.force_angle_degrees, a.slip_angle_degrees, a.normality_residual);
  if (a.gross_sliding && force_drive)
    return fmt::format("θ = {:7.2f}°: no static equilibrium already at the first ramp step; raise ramp_steps",
                       a.angle_degrees);
  if (a.gross_sliding)
    return fmt::format(
        "θ = {:7.2f}°: gross sliding only at the last ramp step; raise pull_displacement to measure the sliding force",
        a.angle_degrees);
  return fmt::format("θ = {:7.2f}°: no gross sliding within the ramp (stick fraction {:.3f} at the end)",
                     a.angle_degrees, a.ramp.empty() ? 1.0 : a.ramp.back().stick_fraction);
}

ExperimentRunResult run_experiment(const ExperimentRunRequest& request) {
  const CaseDescription& description = request.description;
  const auto report = [&](const std::string& line) {
    if (request.report) request.report(line);
  };
  if (!description.experiment)
    throw InvalidInput(
        fmt::format("{}: no [experiment] table; expected one with normal_force, pull_displacement, "
                    "angles_degrees and ramp_steps (docs/experiments.md)",
                    request.case_name));
  study::Tribometer tribometer(description.body, *description.experiment);
  RunDirectory* const run = request.open_run ? request.open_run() : nullptr;
  std::optional<CsvWriter> ramp, polar;
  if (run) {
    ramp.emplace(run->file("tribometer_ramp.csv"),
                 std::vector<std::string>{"angle_degrees", "step", "pull", "normal_force", "tangential_force_x1",
                                          "tangential_force_x2", "force_ratio", "stick_fraction", "num_stick",
                                          "num_slip"});
    polar.emplace(run->file("tribometer_polar.csv"),
                  std::vector<std::string>{"angle_degrees", "gross_sliding", "onset_step", "onset_pull",
                                           "onset_force", "onset_normal_force", "steady_sliding", "sliding_force",
                                           "sliding_normal_force", "force_angle_degrees", "slip_angle_degrees",
                                           "measured_mu", "law_mu", "relative_error", "sliding_resistance",
                                           "law_resistance", "normality_residual"});
    // The law itself, for the polar plot: the radial function μ(φ) of W (the friction force's
    // magnitude per unit P in direction φ) and the support function N_W(θ) (the resistance to
    // sliding along θ).
    CsvWriter law(run->file("tribometer_law.csv"), {"angle_degrees", "radial_mu", "support_mu"},
                  CsvWriter::Mode::kReplace);
    const contact::FrictionLaw& w = description.body.contact->law;
    for (int k = 0; k <= 720; ++k) {
      const double phi = k * 0.5 * std::numbers::pi / 180.0;
      const Eigen::Vector2d d(std::cos(phi), std::sin(phi));
      law.write_row({k * 0.5, w.max_step(Eigen::Vector2d::Zero(), 1.0, d), w.support(d)});
    }
    law.finish();
  }
  const study::TribometerDrive drive = description.experiment->drive;
  ExperimentRunResult result;
  result.summary = tribometer.run([&](const study::TribometerAngleResult& a) {
    if (run) {
      for (std::size_t k = 0; k < a.ramp.size(); ++k) {
        const auto& pt = a.ramp[k];
        ramp->write_row({a.angle_degrees, double(k + 1), pt.pull, pt.normal_force, pt.tangential_force(0),
                         pt.tangential_force(1), pt.tangential_force.norm() / pt.normal_force, pt.stick_fraction,
                         double(pt.num_stick), double(pt.num_slip)});
      }
      polar->write_row({a.angle_degrees, a.gross_sliding ? 1.0 : 0.0, double(a.onset_step + 1), a.onset_pull,
                        a.onset_force, a.onset_normal_force, a.steady_sliding ? 1.0 : 0.0, a.sliding_force,
                        a.sliding_normal_force, a.force_angle_degrees, a.slip_angle_degrees, a.measured_coefficient,
                        a.law_coefficient, a.coefficient_error, a.sliding_resistance, a.law_resistance,
                        a.normality_residual});
    }
    report(describe_angle(a, drive));
  });
  report(result.summary.brief_report());
  // Two coefficients are called μ(θ) (docs/contact.md, "Two meanings of μ(θ)").
  report("radial μ(φ): the friction set's boundary in the force's direction φ, |T| = μ(φ)·P at sliding "
         "(law_mu, radial_mu); the resistance to sliding along θ is the support function N_W(θ) "
         "(law_resistance, support_mu; Python's FrictionLaw.mu)");
  JsonValue json = JsonValue::object();
  json["case"] = request.case_name;
  json["command"] = "experiment";
  add_members(json, run_environment());
  json["drive"] = std::string(study::to_string(drive));
  add_members(json, to_json(result.summary));
  if (run) {
    run->write_json_file(RunDirectory::kSummary, json);
    report(fmt::format("wrote {}, {}, {}", run->file("tribometer_polar.csv").string(),
                       run->file("tribometer_ramp.csv").string(), run->file("tribometer_law.csv").string()));
  }
  result.summary_json = std::move(json);
  return result;
}

}  // namespace frictopt::io
