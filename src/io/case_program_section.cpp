// SPDX-License-Identifier: MIT
#include "case_program_section.hpp"

#include <fmt/format.h>

#include <cmath>

#include "frictopt/core/error.hpp"

namespace frictopt::io::detail {
namespace {

Eigen::VectorXd dim_vector(const TableReader& r, std::string_view key, int dim,
                           std::string_view meaning) {
  const std::string what = fmt::format("a list of {} finite numbers ({})", dim, meaning);
  const std::vector<double> v = r.number_list(key, what);
  if (static_cast<int>(v.size()) != dim) r.fail_value(key, what);
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i])) r.fail_entry(key, i, "a finite number");
  return Eigen::Map<const Eigen::VectorXd>(v.data(), dim);
}

fem::NodalForce read_force(const TableReader& r, int dim) {
  fem::NodalForce f;
  f.force = dim_vector(r, "force", dim, "force, N");
  if (r.has("at"))
    f.where.point = dim_vector(r, "at", dim, "reference coordinates of the point, m");
  if (r.has("box_min")) f.where.box_min = dim_vector(r, "box_min", dim, "lower corner, m");
  if (r.has("box_max")) f.where.box_max = dim_vector(r, "box_max", dim, "upper corner, m");
  if (r.has("boundary"))
    f.where.boundary = r.required_string("boundary", "the name of a boundary set");
  if (const auto t = r.optional_number("tolerance")) {
    if (!(*t >= 0.0)) r.fail_value("tolerance", "a distance >= 0 m");
    f.where.tolerance = *t;
  } else if (f.where.point) {
    r.fail_missing("tolerance", "the largest distance in m from `at` to the node it selects");
  }
  const int selectors = int(f.where.point.has_value()) + int(f.where.box_min || f.where.box_max) +
                        int(f.where.boundary.has_value());
  if (selectors != 1)
    r.fail("force",
           fmt::format("{} selects nodes {} ways; expected exactly one of `at` (+ `tolerance`), "
                       "`box_min` + `box_max`, or `boundary`",
                       r.path(), selectors));
  if ((f.where.box_min.has_value()) != (f.where.box_max.has_value()))
    r.fail("force", fmt::format("{}: a box needs both box_min and box_max", r.path()));
  return f;
}

fem::NodalConstraint read_constraint(const TableReader& r, int dim) {
  fem::NodalConstraint c;
  if (r.has("at"))
    c.where.point = dim_vector(r, "at", dim, "reference coordinates of the point, m");
  if (r.has("box_min")) c.where.box_min = dim_vector(r, "box_min", dim, "lower corner, m");
  if (r.has("box_max")) c.where.box_max = dim_vector(r, "box_max", dim, "upper corner, m");
  if (r.has("boundary"))
    c.where.boundary = r.required_string("boundary", "the name of a boundary set");
  if (const auto t = r.optional_number("tolerance")) {
    if (!(*t >= 0.0)) r.fail_value("tolerance", "a distance >= 0 m");
    c.where.tolerance = *t;
  } else if (c.where.point) {
    r.fail_missing("tolerance", "the largest distance in m from `at` to the node it selects");
  }
  if (r.has("displacement")) c.displacement = dim_vector(r, "displacement", dim, "displacement, m");
  if (r.has("components")) {
    c.components = r.int_list(
        "components", fmt::format("a non-empty list of component indices in 0..{}", dim - 1));
    if (c.components.empty()) r.fail_value("components", "a non-empty list of component indices");
    for (std::size_t i = 0; i < c.components.size(); ++i)
      if (c.components[i] < 0 || c.components[i] >= dim)
        r.fail_entry("components", i, fmt::format("an index in 0..{}", dim - 1));
  }
  const int selectors = int(c.where.point.has_value()) + int(c.where.box_min || c.where.box_max) +
                        int(c.where.boundary.has_value());
  if (selectors != 1)
    r.fail("constraint",
           fmt::format("{} selects nodes {} ways; expected exactly one of `at` (+ `tolerance`), "
                       "`box_min` + `box_max`, or `boundary`",
                       r.path(), selectors));
  return c;
}

std::vector<double> scales(const TableReader& r, std::string_view key) {
  if (!r.has(key)) return {};
  const std::vector<double> v = r.number_list(key, "a list of finite scale factors");
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i])) r.fail_entry(key, i, "a finite number");
  if (v.empty())
    r.fail_value(key,
                 "a non-empty list of scale factors (omit the key to keep the previous step's)");
  return v;
}

study::TribometerDefinition read_experiment(const TableReader& r) {
  study::TribometerDefinition e;
  if (const auto drive = r.optional_string("drive")) {
    try {
      e.drive = study::parse_tribometer_drive(*drive);
    } catch (const InvalidInput& error) {
      r.fail("drive", error.what());
    }
  }
  e.normal_force =
      r.required_number("normal_force", "the normal force P > 0 in N the platen presses with");
  if (e.drive == study::TribometerDrive::kDisplacement) {
    // Optional: without it the run chooses the pull from the law and the specimen and ramps on
    // until the specimen slides steadily (study::Tribometer::automatic_pull_displacement).
    if (const auto pull = r.optional_number("pull_displacement")) e.pull_displacement = *pull;
  } else
    e.max_force_ratio = r.required_number(
        "max_force_ratio", "the ramp's final pull force as a multiple of the normal force, > 0");
  if (const auto t = r.optional_number("onset_tolerance")) e.onset_tolerance = *t;
  if (r.has("angles_degrees"))
    e.angles_degrees = r.number_list("angles_degrees", "a non-empty list of angles in degrees");
  if (const auto n = r.optional_int("ramp_steps")) e.ramp_steps = *n;
  try {
    e.validate();
  } catch (const InvalidInput& error) {
    const std::string_view what = error.what();
    const char* field = "normal_force";
    for (const char* f : {"ramp_steps", "angles_degrees", "pull_displacement", "max_force_ratio", "onset_tolerance"})
      if (what.starts_with(std::string("experiment.") + f)) field = f;
    r.fail(field, error.what());
  }
  return e;
}

}  // namespace

study::LoadingProgramDefinition read_program(const TableReader& r, std::string_view origin,
                                             const study::BodyDefinition& body, std::string_view where) {
  const std::string tables = study::step_tables(where);
  study::LoadingProgramDefinition program;
  const toml::array* steps = r.optional_table_array("step", study::kMaxProgramSteps);
  if (steps == nullptr || steps->empty())
    r.fail_missing("step", "at least one " + tables + " table (a program with no steps solves nothing)");
  for (std::size_t k = 0; k < steps->size(); ++k) {
    const toml::table* t = steps->get(k)->as_table();
    if (t == nullptr) r.fail("step", fmt::format("{}.step[{}] is not a table; expected {} tables", where, k, tables));
    const TableReader s(*t, fmt::format("{}.step[{}]", where, k), origin,
                        {"label", "load_scale", "dirichlet_scale", "force_scale", "friction"});
    study::LoadStepDefinition step;
    step.label = s.optional_string("label").value_or("");
    step.load_scale = scales(s, "load_scale");
    step.dirichlet_scale = scales(s, "dirichlet_scale");
    step.force_scale = scales(s, "force_scale");
    step.friction = s.optional_bool("friction").value_or(true);
    program.steps.push_back(std::move(step));
  }
  try {
    program.validate(body, where);
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("{}: {}", origin, e.what()));
  }
  return program;
}

void read_program_sections(const TableReader& top, std::string_view origin, int dim,
                           CaseDescription& c) {
  if (const toml::array* forces = top.optional_table_array("force", kMaxBodyTables))
    for (std::size_t i = 0; i < forces->size(); ++i)
      c.body.forces.push_back(
          read_force(TableReader(*forces->get(i)->as_table(), fmt::format("force[{}]", i), origin,
                                 {"at", "tolerance", "box_min", "box_max", "boundary", "force"}),
                     dim));
  if (const toml::array* constraints = top.optional_table_array("constraint", kMaxBodyTables))
    for (std::size_t i = 0; i < constraints->size(); ++i)
      c.body.constraints.push_back(read_constraint(
          TableReader(
              *constraints->get(i)->as_table(), fmt::format("constraint[{}]", i), origin,
              {"at", "tolerance", "box_min", "box_max", "boundary", "components", "displacement"}),
          dim));
  if (const toml::table* program = top.optional_table("program"))
    c.program = read_program(TableReader(*program, "program", origin, {"step"}), origin, c.body, "program");
  if (const toml::table* experiment = top.optional_table("experiment"))
    c.experiment = read_experiment(
        TableReader(*experiment, "experiment", origin,
                    {"drive", "normal_force", "pull_displacement", "max_force_ratio", "angles_degrees",
                     "ramp_steps", "onset_tolerance"}));
}

}  // namespace frictopt::io::detail
