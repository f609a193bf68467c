// SPDX-License-Identifier: MIT
#include "case_identification_section.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "frictopt/core/error.hpp"
#include "frictopt/io/measurements.hpp"

namespace frictopt::io::detail {
namespace {

// A file name resolved against the case file's directory (as [mesh] file and the CSV always were).
std::filesystem::path resolved(std::string_view origin, const std::string& file) {
  std::filesystem::path path(file);
  const std::filesystem::path origin_path(origin);
  if (path.is_relative() && origin_path.has_parent_path()) path = origin_path.parent_path() / path;
  return path;
}

// One inline row: the fields of a CSV row (docs/identification.md, "The measurement file"), with
// `location` spelt as in the CSV ("12", "x=0.5;0.5", "all"), or a node index, or a point [x1, x2].
study::Measurement read_measurement(const TableReader& r, std::string_view origin) {
  study::Measurement m;
  const toml::node* where_node = &r.table();
  m.label = located(origin, where_node, r.path());
  const std::string quantity = r.required_string("quantity", "a measured quantity (docs/identification.md)");
  try {
    m.quantity = study::parse_measured_quantity(quantity);
  } catch (const InvalidInput& e) {
    r.fail("quantity", fmt::format("{}: {}", r.path(), e.what()));
  }
  if (const toml::node* location = r.node("location")) {
    if (const auto* text = location->as_string()) {
      try {
        parse_location(m, text->get(), r.path());
      } catch (const InvalidInput& e) {
        r.fail("location", e.what());
      }
    } else if (const auto* node = location->as_integer()) {
      if (study::is_total(m.quantity))
        r.fail_value("location", fmt::format("\"all\" or no location for the sum {}", quantity));
      if (node->get() < 0 || node->get() > std::numeric_limits<int>::max())
        r.fail_value("location", "a contact-node index >= 0");
      m.node = static_cast<int>(node->get());
    } else if (location->is_array()) {
      if (study::is_total(m.quantity))
        r.fail_value("location", fmt::format("\"all\" or no location for the sum {}", quantity));
      const std::vector<double> x = r.number_list("location", "a point [x1, x2] (2D: [x1]) on the contact surface [m]");
      if (x.empty() || x.size() > 2) r.fail_value("location", "a point [x1, x2] (2D: [x1]) on the contact surface [m]");
      for (std::size_t k = 0; k < x.size(); ++k)
        if (!std::isfinite(x[k])) r.fail_entry("location", k, "a finite coordinate [m]");
      m.point = Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
    } else {
      r.fail_value("location", "a contact-node index, a point [x1, x2], or a string as in the CSV (\"12\", "
                               "\"x=0.5;0.5\", \"all\")");
    }
  } else if (!study::is_total(m.quantity)) {
    r.fail_missing("location", fmt::format("the location of the {} measurement: a contact-node index, a point [x1, x2] "
                                           "or \"x=x1;x2\"",
                                           quantity));
  }
  m.value = r.required_number("value", "the measured value (a finite number)");
  if (!std::isfinite(m.value)) r.fail_value("value", "a finite number");
  m.sigma = r.required_number("sigma", "the standard deviation of the value (> 0, same unit)");
  if (!(m.sigma > 0 && std::isfinite(m.sigma))) r.fail_value("sigma", "a standard deviation > 0");
  return m;
}

// The measurements of an experiment (or of [identification] itself): `measurements` (a CSV file)
// and the [[...measurement]] rows.
void read_measurement_sources(const TableReader& r, std::string_view origin, IdentificationExperimentSetup& out) {
  if (const auto file = r.optional_string("measurements")) {
    if (file->empty()) r.fail_value("measurements", "a non-empty path of a measurement CSV");
    out.measurements = resolved(origin, *file);
  }
  if (const toml::array* rows = r.optional_table_array("measurement", study::kMaxMeasurements))
    for (std::size_t i = 0; i < rows->size(); ++i)
      out.inline_measurements.push_back(read_measurement(
          TableReader(*rows->get(i)->as_table(), fmt::format("{}[{}]", r.field("measurement"), i), origin,
                      {"quantity", "location", "value", "sigma"}),
          origin));
}

// load_scale / dirichlet_scale / force_scale: a number (every table of the kind) or one per table.
std::vector<double> read_scales(const TableReader& r, std::string_view key, std::size_t count, std::string_view table) {
  const toml::node* node = r.node(key);
  if (node == nullptr) return {};
  if (count == 0)
    r.fail(key, fmt::format("{} = {}: the case has no [[{}]] table to scale; expected no {}", r.field(key),
                            describe(*node), table, key));
  const std::string what = fmt::format("a number (every [[{}]] table) or a list of {} numbers (one per table)", table, count);
  std::vector<double> v = node->is_array() ? r.number_list(key, what) : std::vector<double>{r.required_number(key, what)};
  if (v.size() != 1 && v.size() != count) r.fail_value(key, what);
  for (std::size_t j = 0; j < v.size(); ++j)
    if (!std::isfinite(v[j])) {
      if (!node->is_array()) r.fail_value(key, "a finite number");
      r.fail_entry(key, j, "a finite number");
    }
  return v;
}

// The file-name-safe characters of an experiment name (--generate-synthetic writes NAME.csv).
bool valid_name(const std::string& name) {
  if (name.empty() || name.size() > 64 || name.front() == '.') return false;
  return std::all_of(name.begin(), name.end(), [](char ch) {
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_' ||
           ch == '-' || ch == '.';
  });
}

IdentificationExperimentSetup read_experiment(const TableReader& r, std::string_view origin, const CaseDescription& c,
                                              std::size_t k) {
  IdentificationExperimentSetup x;
  x.name = fmt::format("experiment_{}", k);
  if (const auto name = r.optional_string("name")) {
    if (!valid_name(*name))
      r.fail_value("name", "a name of 1 to 64 letters, digits, '_', '-' or '.' (not starting with '.'): it names the "
                           "file --generate-synthetic writes");
    x.name = *name;
  }
  if (const auto angle = r.optional_number("orientation_deg")) {
    if (!(std::isfinite(*angle) && std::abs(*angle) <= 360.0))
      r.fail_value("orientation_deg", "an angle in [-360, 360] degrees");
    if (*angle != 0.0 && c.dim() == 2)
      r.fail_value("orientation_deg", "0 in 2D (the friction law of a contact line has no in-plane rotation)");
    x.orientation = *angle * std::numbers::pi / 180.0;
  }
  x.load_scale = read_scales(r, "load_scale", c.body.tractions.size(), "load");
  x.dirichlet_scale = read_scales(r, "dirichlet_scale", c.body.dirichlet.size(), "dirichlet");
  x.force_scale = read_scales(r, "force_scale", c.body.forces.size(), "force");
  read_measurement_sources(r, origin, x);
  if (!x.has_measurements())
    r.fail_missing("measurements", fmt::format("the measurements of experiment \"{}\": measurements = \"file.csv\" or "
                                               "[[{}]] tables",
                                               x.name, r.field("measurement")));
  return x;
}

// [identification.parameters.<name>]: one study::ParameterSpec per identified scalar
// ("mu_vertices" one per vertex). The names depend on the friction kind, so a misspelt or foreign
// name is reported with the valid ones.
void read_parameters(const TableReader& r, const CaseDescription& c, std::string_view kind, std::size_t num_vertices,
                     study::Identification::Options& options) {
  const int dim = c.dim();
  std::vector<std::string_view> names;
  if (kind == "isotropic" || kind == "polygon") {
    if (dim == 2) names = {"mu_minus", "mu_plus"};  // the 2D laws are intervals [−μ₋, μ₊]
    else if (kind == "isotropic") names = {"mu"};
    else names = {"mu_vertices"};
  } else if (kind == "disc_exact") {
    names = {"mu"};
  } else if (kind == "ellipse" || kind == "ellipse_exact") {
    names = {"mu_x", "mu_y"};
  }
  names.push_back("young");
  std::string accepted;
  for (std::string_view n : names) accepted += (accepted.empty() ? "" : ", ") + std::string(n);

  const toml::table* parameters = r.optional_table("parameters");
  if (parameters == nullptr || parameters->empty())
    r.fail_missing("parameters", fmt::format("a table [identification.parameters.<name>] per parameter to identify, "
                                             "<name> one of {} for contact.friction.kind = \"{}\"",
                                             accepted, kind));
  for (auto&& [key, node] : *parameters) {
    const std::string name(key.str());
    const std::string field = r.field("parameters") + "." + name;
    if (std::find(names.begin(), names.end(), name) == names.end())
      throw InvalidInput(located(c.origin, &node,
                                 fmt::format("{}: unknown parameter \"{}\" for contact.friction.kind = \"{}\" in {}D; "
                                             "expected one of {}",
                                             field, name, kind, dim, accepted)));
    if (!node.is_table())
      throw InvalidInput(located(c.origin, &node,
                                 fmt::format("{} = {}; expected a table with lower, upper and optionally initial", field,
                                             describe(node))));
    const TableReader t(*node.as_table(), field, c.origin, {"initial", "lower", "upper"});
    const bool per_vertex = name == "mu_vertices";
    const std::size_t count = per_vertex ? num_vertices : 1;
    const auto values = [&](std::string_view k, bool required) -> std::vector<double> {
      const std::string what = count == 1 ? "a number" : fmt::format("a number or a list of {} numbers (one per vertex)", count);
      const toml::node* v = t.node(k);
      if (v == nullptr) {
        if (required) t.fail_missing(k, what);
        return {};
      }
      std::vector<double> out = v->is_array() && count > 1 ? t.number_list(k, what)
                                                            : std::vector<double>{t.required_number(k, what)};
      if (out.size() != 1 && out.size() != count) t.fail_value(k, what);
      for (std::size_t j = 0; j < out.size(); ++j)
        if (!std::isfinite(out[j])) {
          if (out.size() == 1) t.fail_value(k, "a finite number");
          t.fail_entry(k, j, "a finite number");
        }
      return out;
    };
    struct {
      std::vector<double> lower, upper, initial;  // 1 entry (every vertex) or one per vertex
    } p;
    p.lower = values("lower", true);
    p.upper = values("upper", true);
    p.initial = values("initial", false);
    const auto at = [](const std::vector<double>& v, std::size_t j) { return v.size() == 1 ? v[0] : v[j]; };
    const auto entry = [&](std::string_view k, const std::vector<double>& v, std::size_t j) {
      return v.size() == 1 ? std::string(k) : fmt::format("{}[{}]", k, j);
    };
    for (std::size_t j = 0; j < count; ++j) {
      const double lo = at(p.lower, j), hi = at(p.upper, j);
      if (name == "young" ? !(lo > 0) : !(lo >= 0))
        t.fail("lower",
               fmt::format("{}.{} = {}; expected {}", field, entry("lower", p.lower, j), lo, name == "young" ? "> 0" : ">= 0"));
      if (!(lo <= hi))
        t.fail("upper", fmt::format("{}: lower bound {} = {} > upper bound {} = {}; expected lower <= upper", field,
                                    entry("lower", p.lower, j), lo, entry("upper", p.upper, j), hi));
      if (!p.initial.empty() && !(at(p.initial, j) >= lo && at(p.initial, j) <= hi))
        t.fail("initial", fmt::format("{}.{} = {}; expected within [{}, {}]", field, entry("initial", p.initial, j),
                                      at(p.initial, j), lo, hi));
    }
    for (std::size_t j = 0; j < count; ++j) {
      study::ParameterSpec scalar;
      scalar.name = per_vertex ? fmt::format("mu_vertices[{}]", j) : name;
      if (!p.initial.empty()) scalar.initial = at(p.initial, j);
      scalar.lower = at(p.lower, j);
      scalar.upper = at(p.upper, j);
      options.parameters.push_back(scalar);
    }
  }
}

}  // namespace

void read_identification_section(const TableReader& top, std::string_view origin, CaseDescription& c,
                                 std::string_view friction_kind, std::size_t num_vertices) {
  const toml::table* table = top.optional_table("identification");
  if (table == nullptr) return;
  const TableReader r(*table, "identification", origin,
                      {"measurements", "measurement", "experiment", "parameters", "loss", "loss_scale",
                       "max_iterations"});
  IdentificationSetup spec;
  study::Identification::Options& options = spec.options;
  if (friction_kind.empty())
    r.fail("parameters", fmt::format("{}: [identification] needs a [contact] table (the measured quantities are "
                                     "contact forces and slips)",
                                     origin));
  if (const toml::array* experiments = r.optional_table_array("experiment", study::kMaxIdentificationExperiments)) {
    // Several experiments: each names its own measurements, so [identification] names none.
    for (const char* key : {"measurements", "measurement"})
      if (r.has(key))
        r.fail(key, fmt::format("{} with [[identification.experiment]] tables; expected the measurements inside each "
                                "experiment (its own measurements = \"file.csv\" or [[identification.experiment."
                                "measurement]] rows)",
                                r.field(key)));
    if (experiments->empty()) r.fail_value("experiment", "at least one [[identification.experiment]] table");
    spec.experiments.clear();
    spec.explicit_experiments = true;
    for (std::size_t k = 0; k < experiments->size(); ++k) {
      const TableReader e(*experiments->get(k)->as_table(), fmt::format("{}[{}]", r.field("experiment"), k), origin,
                          {"name", "orientation_deg", "load_scale", "dirichlet_scale", "force_scale", "measurements",
                           "measurement"});
      spec.experiments.push_back(read_experiment(e, origin, c, k));
      for (std::size_t j = 0; j < k; ++j)
        if (spec.experiments[j].name == spec.experiments[k].name)
          e.fail("name", fmt::format("{}.name = \"{}\" is the name of identification.experiment[{}]; expected unique "
                                     "names",
                                     e.path(), spec.experiments[k].name, j));
    }
  } else {
    // One experiment, the case's loads; its measurements may also come from Python (none here).
    read_measurement_sources(r, origin, spec.experiments.front());
  }
  if (const auto loss = r.optional_string("loss")) {
    try {
      options.loss = study::parse_robust_loss(*loss);
    } catch (const InvalidInput&) {
      r.fail_value("loss", "one of none, huber, cauchy");
    }
  }
  if (const auto scale = r.optional_number("loss_scale")) {
    if (!(*scale > 0)) r.fail_value("loss_scale", "loss_scale > 0 (in standard deviations)");
    options.loss_scale = *scale;
  }
  if (const std::optional<int> n = r.optional_int("max_iterations")) {
    if (*n < 1) r.fail_value("max_iterations", "max_iterations >= 1");
    options.max_iterations = *n;
  }
  read_parameters(r, c, friction_kind, num_vertices, options);
  c.identification = std::move(spec);
}

}  // namespace frictopt::io::detail
