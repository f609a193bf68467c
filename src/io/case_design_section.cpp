// SPDX-License-Identifier: MIT
#include "case_design_section.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "frictopt/core/error.hpp"

namespace frictopt::io::detail {
namespace {

constexpr int kMaxControlPointsPerDirection = 64;  // Bernstein degree 63
constexpr std::int64_t kMaxDesignVariables = 1024;  // the bundle QP is dense in d

// [design] into the body: the Bézier shape over the geometry's base, Υ and α⁰.
void read_design(const TableReader& r, const Geometry& g, study::BodyDefinition& body) {
  shape::AdmissibleSetParameters& d = body.admissible;
  d.height = g.height;
  const int dim = g.dim;
  const std::string what =
      dim == 2 ? "a list [m1] of 1 integer >= 2 in 2D" : "a list [m1, m2] of 2 integers >= 2 in 3D";
  const std::vector<int> control_points = r.int_list("control_points", what);
  if (static_cast<int>(control_points.size()) != dim - 1) r.fail_value("control_points", what);
  std::int64_t num_controls = 1;
  for (std::size_t i = 0; i < control_points.size(); ++i) {
    if (control_points[i] < 2 || control_points[i] > kMaxControlPointsPerDirection)
      r.fail_entry("control_points", i,
                   fmt::format("an integer in [2, {}] (Bézier degree <= {})", kMaxControlPointsPerDirection,
                               kMaxControlPointsPerDirection - 1));
    num_controls *= control_points[i];
  }
  if (num_controls > kMaxDesignVariables)
    r.fail_value("control_points", fmt::format("at most {} design variables in all; this net has {}",
                                               kMaxDesignVariables, num_controls));
  body.shape = dim == 2 ? shape::BezierShape::curve(g.a, control_points[0])
                        : shape::BezierShape::surface(g.a, g.b, control_points[0], control_points[1]);

  d.upper_bound = r.required_number("upper_bound", "a number > 0 (the bound C0 on α, m)");
  if (!(d.upper_bound > 0 && d.upper_bound < g.height))
    r.fail_value("upper_bound", fmt::format("0 < upper_bound < geometry.height = {} (a control "
                                            "point at the top would collapse the body)",
                                            g.height));

  const int m = body.shape.num_controls();
  const std::string initial_what =
      fmt::format("a number or a list of {} numbers (the initial heights α⁰, m)", m);
  const toml::node* initial = r.node("initial");
  if (initial == nullptr) r.fail_missing("initial", initial_what);
  const std::string range = fmt::format("0 <= α <= upper_bound = {}", d.upper_bound);
  if (initial->as_array()) {
    const std::vector<double> values = r.number_list("initial", initial_what);
    if (static_cast<int>(values.size()) != m) r.fail_value("initial", initial_what);
    for (std::size_t i = 0; i < values.size(); ++i)
      if (!(values[i] >= 0 && values[i] <= d.upper_bound)) r.fail_entry("initial", i, range);
    body.initial_design = Eigen::Map<const Eigen::VectorXd>(values.data(), m);
  } else {
    const double value = r.required_number("initial", initial_what);
    if (!(value >= 0 && value <= d.upper_bound)) r.fail_value("initial", range);
    body.initial_design = Eigen::VectorXd::Constant(m, value);
  }

  if (auto c1 = r.optional_number("slope_bound")) {
    if (!(*c1 > 0)) r.fail_value("slope_bound", "slope_bound > 0 (omit it for no slope bound)");
    d.slope_bound = c1;
  }
  if (auto c2 = r.optional_number("volume")) {
    // meas Ω(α) = A·(height − mean of G_α) and 0 <= G_α <= C0 (convex-hull property,
    // docs/theory/problem.md §2), so only this interval is reachable; outside it Υ is empty (the
    // trap of the thesis' printed formula, docs/theory/problem.md §6).
    const double base = dim == 2 ? g.a : g.a * g.b;
    const double lo = base * (g.height - d.upper_bound);
    const double hi = base * g.height;
    if (!(*c2 >= lo && *c2 <= hi))
      r.fail_value("volume", fmt::format("{} <= volume <= {} (the {} reachable with 0 <= α <= C0: "
                                         "{}·(height − C0) to {}·height)",
                                         lo, hi, dim == 2 ? "area" : "volume",
                                         dim == 2 ? "a" : "a·b", dim == 2 ? "a" : "a·b"));
    d.volume = c2;
  }
  if (auto s = read_enum(r, "slope_scaling", shape::kSlopeScalingNames)) d.slope_scaling = *s;

  // friction_orientation (docs/theory/friction-design.md): the law's orientation φ is a design
  // variable too, within [orientation_lower_deg, orientation_upper_deg]; the law itself is checked
  // once the [contact] table is read (study::OrientationDesign).
  const bool orientation = r.optional_bool("friction_orientation").value_or(false);
  const std::optional<double> lower = r.optional_number("orientation_lower_deg");
  const std::optional<double> upper = r.optional_number("orientation_upper_deg");
  if (!orientation) {
    if (lower) r.fail("orientation_lower_deg", "orientation_lower_deg without friction_orientation = true; expected "
                                               "friction_orientation = true or no orientation bounds");
    if (upper) r.fail("orientation_upper_deg", "orientation_upper_deg without friction_orientation = true; expected "
                                               "friction_orientation = true or no orientation bounds");
    return;
  }
  if (!lower) r.fail_missing("orientation_lower_deg", "the lower bound on the law's orientation φ, degrees");
  if (!upper) r.fail_missing("orientation_upper_deg", "the upper bound on the law's orientation φ, degrees");
  if (!(std::abs(*lower) <= 360.0)) r.fail_value("orientation_lower_deg", "an angle in degrees in [−360, 360]");
  if (!(std::abs(*upper) <= 360.0)) r.fail_value("orientation_upper_deg", "an angle in degrees in [−360, 360]");
  if (!(*lower < *upper))
    r.fail_value("orientation_upper_deg", fmt::format("orientation_upper_deg > orientation_lower_deg = {}", *lower));
  body.friction_orientation = study::OrientationDesignDefinition{*lower * std::numbers::pi / 180.0,
                                                                 *upper * std::numbers::pi / 180.0};
}

}  // namespace

void read_design_section(const TableReader& top, std::string_view origin, const Geometry& geometry,
                         study::BodyDefinition& body) {
  read_design(required_table(top, "design", origin,
                             {"control_points", "initial", "upper_bound", "slope_bound", "volume", "slope_scaling",
                              "friction_orientation", "orientation_lower_deg", "orientation_upper_deg"}),
              geometry, body);
}

}  // namespace frictopt::io::detail
