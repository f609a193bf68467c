// SPDX-License-Identifier: MIT
#include "case_optimization_section.hpp"

#include <fmt/format.h>

#include "frictopt/core/error.hpp"

namespace frictopt::io::detail {
namespace {

// [optimization]: overrides of the bundle trust options (the study's defaults otherwise).
void read_optimization(const TableReader& r, optim::BundleTrust::Options& o) {
  if (const std::optional<int> n = r.optional_int("max_iterations")) {
    if (*n < 1) r.fail_value("max_iterations", "max_iterations >= 1");
    o.max_iterations = *n;
  }
  if (const std::optional<int> n = r.optional_int("max_evaluations")) {
    if (*n < 1) r.fail_value("max_evaluations", "max_evaluations >= 1");
    o.max_evaluations = *n;
  }
  if (const std::optional<double> eps = r.optional_number("epsilon")) {
    if (!(*eps > 0)) r.fail_value("epsilon", "epsilon > 0");
    o.epsilon = *eps;
  }
  if (const std::optional<double> t = r.optional_number("max_step_length")) {
    if (!(*t > 0)) r.fail_value("max_step_length", "max_step_length > 0");
    o.max_step_length = *t;
  }
  if (const std::optional<int> n = r.optional_int("bundle_size")) {
    if (*n < 3) r.fail_value("bundle_size", "bundle_size >= 3");
    o.max_bundle_size = *n;
  }
  // The opt-in diagonal variable metric of the proximal term (docs/optim.md, "Variable metric").
  if (const std::optional<bool> b = r.optional_bool("variable_metric")) o.variable_metric = *b;
  // Worst-case load cases: the other cases' cuts in the bundle (docs/optim.md, "Cuts of the
  // pieces of a max"); off saves K − 1 adjoints per evaluation.
  if (const std::optional<bool> b = r.optional_bool("case_cuts")) o.use_piece_cuts = *b;
  // The default confirmation of a stop in the point's units when they spread by more than
  // point_units_spread (docs/optim.md, "Confirmation in the point's units").
  if (const std::optional<bool> b = r.optional_bool("confirm_in_point_units")) o.confirm_in_point_units = *b;
  if (const std::optional<double> k = r.optional_number("point_units_spread")) {
    if (!(*k >= 1.0) || !std::isfinite(*k)) r.fail_value("point_units_spread", "point_units_spread >= 1 (finite)");
    o.point_units_spread = *k;
  }
}

}  // namespace

void read_optimization_section(const TableReader& top, std::string_view origin, optim::BundleTrust::Options& options) {
  const toml::table* table = top.optional_table("optimization");
  if (table == nullptr) return;
  read_optimization(TableReader(*table, "optimization", origin,
                                {"max_iterations", "max_evaluations", "epsilon", "max_step_length", "bundle_size",
                                 "variable_metric", "case_cuts", "confirm_in_point_units", "point_units_spread"}),
                    options);
}

}  // namespace frictopt::io::detail
