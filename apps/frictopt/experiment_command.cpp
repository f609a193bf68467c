// SPDX-License-Identifier: MIT
// `frictopt experiment` (the virtual tribometer) and `frictopt solve` of a case with a loading
// program: see apps/frictopt/commands.hpp and docs/experiments.md.
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "commands.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/csv_writer.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/io/run_directory.hpp"
#include "frictopt/io/state_output.hpp"
#include "frictopt/io/summary_json.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/loading_program.hpp"
#include "frictopt/study/tribometer.hpp"

namespace frictopt::app {

int run_program(const std::filesystem::path& case_path, const std::filesystem::path& out_dir,
                const io::CaseDescription& description) {
  study::ElasticBody body(description.body);
  study::LoadingProgram program(body, *description.program);
  io::RunDirectory run(out_dir, io::RunOpening::kOutput, case_path);
  const std::string name = body.definition().name;
  std::vector<std::string> notes;
  if (description.output.vtk) run.start_series(name, 0, notes);
  io::JsonValue steps = io::JsonValue::array();
  const study::LoadingProgram::Summary summary =
      program.run(body.definition().initial_design, [&](const study::LoadStepResult& r) {
        fmt::print("{} ({}): {}\n", r.label, r.step, r.state.summary.brief_report());
        io::JsonValue step = io::solve_summary(case_path.string(), body, r.state);
        step["command"] = "solve (loading program)";
        step["step"] = r.step;
        step["label"] = r.label;
        step["external_work"] = r.external_work;
        if (r.state.contact) {
          fmt::print("  {}\n  {}\n", r.state.contact->summary.brief_report(),
                     r.state.contact->resultants.brief_report());
        }
        steps.push_back(step);
        if (description.output.vtk && r.state.summary.status == Status::kConverged)
          run.add_to_series(r.step, [&](const std::filesystem::path& vtu) {
            io::write_state_vtu(vtu, body, r.state);
          });
      });
  fmt::print("{}\n", summary.brief_report());
  io::JsonValue json = io::JsonValue::object();
  json["case"] = case_path.string();
  json["command"] = "solve";
  io::add_members(json, io::run_environment());
  json["status"] = std::string(to_string(summary.status));
  json["message"] = summary.message;
  json["steps_solved"] = summary.steps_solved;
  json["factorizations"] = summary.factorizations;
  json["factorization_seconds"] = summary.factorization_seconds;
  json["contact_seconds"] = summary.contact_seconds;
  json["time_seconds"] = summary.time_seconds;
  json["steps"] = steps;
  run.write_json_file(io::RunDirectory::kSummary, json);
  if (description.output.vtk) fmt::print("wrote {}\n", run.file(name + ".pvd").string());
  return summary.status == Status::kConverged ? kExitOk : kExitNumericalFailure;
}

int run_experiment(const std::filesystem::path& case_path, const std::filesystem::path& out_dir) {
  const io::CaseDescription description = io::load_case(case_path);
  if (!description.experiment)
    throw InvalidInput(
        fmt::format("{}: no [experiment] table; expected one with normal_force, pull_displacement, "
                    "angles_degrees and ramp_steps (docs/experiments.md)",
                    case_path.string()));
  study::Tribometer tribometer(description.body, *description.experiment);
  io::RunDirectory run(out_dir, io::RunOpening::kOutput, case_path);
  io::CsvWriter ramp(
      run.file("tribometer_ramp.csv"),
      {"angle_degrees", "step", "pull", "normal_force", "tangential_force_x1",
       "tangential_force_x2", "force_ratio", "stick_fraction", "num_stick", "num_slip"});
  io::CsvWriter polar(
      run.file("tribometer_polar.csv"),
      {"angle_degrees", "gross_sliding", "onset_step", "onset_pull", "onset_force",
       "onset_normal_force", "steady_sliding", "sliding_force", "sliding_normal_force",
       "force_angle_degrees", "slip_angle_degrees", "measured_mu", "law_mu", "relative_error",
       "sliding_resistance", "law_resistance", "normality_residual"});
  {
    // The law itself, for the polar plot: the radial function μ(φ) of W (the friction force's
    // magnitude per unit P in direction φ) and the support function N_W(θ) (the resistance to
    // sliding along θ).
    io::CsvWriter law(run.file("tribometer_law.csv"), {"angle_degrees", "radial_mu", "support_mu"},
                      io::CsvWriter::Mode::kReplace);
    const contact::FrictionLaw& w = description.body.contact->law;
    for (int k = 0; k <= 720; ++k) {
      const double phi = k * 0.5 * std::numbers::pi / 180.0;
      const Eigen::Vector2d d(std::cos(phi), std::sin(phi));
      law.write_row({k * 0.5, w.max_step(Eigen::Vector2d::Zero(), 1.0, d), w.support(d)});
    }
    law.finish();
  }
  const study::Tribometer::Summary summary =
      tribometer.run([&](const study::TribometerAngleResult& a) {
        for (std::size_t k = 0; k < a.ramp.size(); ++k) {
          const auto& pt = a.ramp[k];
          ramp.write_row({a.angle_degrees, double(k + 1), pt.pull, pt.normal_force,
                          pt.tangential_force(0), pt.tangential_force(1),
                          pt.tangential_force.norm() / pt.normal_force, pt.stick_fraction,
                          double(pt.num_stick), double(pt.num_slip)});
        }
        polar.write_row({a.angle_degrees, a.gross_sliding ? 1.0 : 0.0, double(a.onset_step + 1),
                         a.onset_pull, a.onset_force, a.onset_normal_force,
                         a.steady_sliding ? 1.0 : 0.0, a.sliding_force, a.sliding_normal_force,
                         a.force_angle_degrees, a.slip_angle_degrees, a.measured_coefficient,
                         a.law_coefficient, a.coefficient_error, a.sliding_resistance,
                         a.law_resistance, a.normality_residual});
        if (a.steady_sliding && description.experiment->drive == study::TribometerDrive::kForce)
          fmt::print(
              "θ = {:7.2f}°: no static equilibrium beyond Q = {:.9e} N (ramp step {}); limit state: |T|/P = "
              "{:.9f}, law radial μ(φ) = {:.9f} (rel. error {:.1e}), force at φ = {:.3f}°, slip at {:.3f}°, normality "
              "{:.1e}, stick fraction {:.3f}\n",
              a.angle_degrees, a.onset_force, a.onset_step + 1, a.measured_coefficient, a.law_coefficient,
              a.coefficient_error, a.force_angle_degrees, a.slip_angle_degrees, a.normality_residual,
              a.ramp.back().stick_fraction);
        else if (a.steady_sliding)
          fmt::print(
              "θ = {:7.2f}°: sliding from step {} (|T| = {:.4e} N); sliding: |T|/P = {:.9f}, law "
              "radial μ(φ) = {:.9f} "
              "(rel. error {:.1e}), force at φ = {:.3f}°, slip at {:.3f}°, normality {:.1e}\n",
              a.angle_degrees, a.onset_step + 1, a.onset_force, a.measured_coefficient,
              a.law_coefficient, a.coefficient_error, a.force_angle_degrees, a.slip_angle_degrees,
              a.normality_residual);
        else if (a.gross_sliding && description.experiment->drive == study::TribometerDrive::kForce)
          fmt::print("θ = {:7.2f}°: no static equilibrium already at the first ramp step; raise ramp_steps\n",
                     a.angle_degrees);
        else if (a.gross_sliding)
          fmt::print(
              "θ = {:7.2f}°: gross sliding only at the last ramp step; raise pull_displacement to "
              "measure the "
              "sliding force\n",
              a.angle_degrees);
        else
          fmt::print(
              "θ = {:7.2f}°: no gross sliding within the ramp (stick fraction {:.3f} at the end)\n",
              a.angle_degrees, a.ramp.empty() ? 1.0 : a.ramp.back().stick_fraction);
      });
  fmt::print("{}\n", summary.brief_report());
  // Two coefficients are called μ(θ) (docs/contact.md, "Two meanings of μ(θ)").
  fmt::print("radial μ(φ): the friction set's boundary in the force's direction φ, |T| = μ(φ)·P at sliding "
             "(law_mu, radial_mu); the resistance to sliding along θ is the support function N_W(θ) "
             "(law_resistance, support_mu; Python's FrictionLaw.mu)\n");
  io::JsonValue json = io::JsonValue::object();
  json["case"] = case_path.string();
  json["command"] = "experiment";
  io::add_members(json, io::run_environment());
  json["drive"] = std::string(study::to_string(description.experiment->drive));
  json["status"] = std::string(to_string(summary.status));
  json["message"] = summary.message;
  json["press_displacement"] = summary.press_displacement;
  json["press_iterations"] = summary.press_iterations;
  json["contact_solves"] = summary.contact_solves;
  json["factorizations"] = summary.factorizations;
  json["time_seconds"] = summary.time_seconds;
  io::JsonValue angles = io::JsonValue::array();
  for (const auto& a : summary.angles) {
    io::JsonValue j = io::JsonValue::object();
    j["angle_degrees"] = a.angle_degrees;
    j["gross_sliding"] = a.gross_sliding;
    j["onset_step"] = a.onset_step + 1;
    j["onset_pull"] = a.onset_pull;
    j["onset_force"] = a.onset_force;
    j["onset_normal_force"] = a.onset_normal_force;
    j["steady_sliding"] = a.steady_sliding;
    j["sliding_force"] = a.sliding_force;
    j["sliding_normal_force"] = a.sliding_normal_force;
    j["sliding_resistance"] = a.sliding_resistance;
    j["law_resistance"] = a.law_resistance;
    j["force_angle_degrees"] = a.force_angle_degrees;
    j["slip_angle_degrees"] = a.slip_angle_degrees;
    j["measured_mu"] = a.measured_coefficient;
    j["law_mu"] = a.law_coefficient;
    j["relative_error"] = a.coefficient_error;
    j["normality_residual"] = a.normality_residual;
    angles.push_back(j);
  }
  json["angles"] = angles;
  run.write_json_file(io::RunDirectory::kSummary, json);
  fmt::print("wrote {}, {}, {}\n", run.file("tribometer_polar.csv").string(),
             run.file("tribometer_ramp.csv").string(), run.file("tribometer_law.csv").string());
  return summary.status == Status::kConverged ? kExitOk : kExitNumericalFailure;
}

}  // namespace frictopt::app
