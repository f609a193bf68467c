// SPDX-License-Identifier: MIT
// `frictopt check-gradient`: see apps/frictopt/commands.hpp.
#include "commands.hpp"

#include <fmt/format.h>
#include <filesystem>
#include <numbers>
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/design_file.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/sensitivity/friction_parameters.hpp"
#include "frictopt/study/certificate.hpp"
#include "frictopt/study/derivative_accuracy.hpp"
#include "frictopt/study/gradient_check.hpp"
#include "frictopt/study/shape_optimization.hpp"
#include "frictopt/study/shape_oracle.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::app {

// frictopt check-gradient: the adjoint subgradient ξ against central differences of Θ, per
// component, with the index sets and |𝕃| at the design (docs/sensitivity.md, "Verification").
// Differences are only meaningful where no node changes piece within ±h: the report lists the
// nodes that do, with both one-sided quotients, and warns when the check cannot mean anything.
int run_check_gradient(const std::filesystem::path& case_path, const std::filesystem::path& design_path,
                       double relative_step) {
  using namespace frictopt;
  const io::CaseDescription description = io::load_case(case_path);
  study::BodyDefinition definition = description.body;
  if (!definition.contact) throw InvalidInput(case_path.string() + ": check-gradient needs a [contact] table");
  // Finite differences need a state far more accurate than the step.
  study::tighten_for_derivatives(definition.contact->coulomb);
  study::ElasticBody body(definition);
  const Eigen::VectorXd alpha = design_path.empty() ? body.initial_design()
                                                    : io::read_design_file(design_path, body.num_design_variables());
  // The same admissibility check as certify: Θ and ξ are defined on Υ only.
  study::require_admissible_design(body, alpha, study::CertifyOptions{}.active_tolerance,
                                   design_path.empty() ? case_path.string() + ": design.initial" : design_path.string());
  study::ShapeOracle oracle(body, description.required_cost());
  const study::GradientCheck check = study::check_gradient(oracle, alpha, relative_step);
  const study::Evaluation& e = check.evaluation;
  fmt::print("{}: cost {}, Θ = {:.10e}\n", case_path.string(), oracle.cost().name(), e.value);
  if (const study::LoadCases* cases = oracle.load_cases())  // every load case's J_k
    for (std::size_t k = 0; k < e.case_values.size(); ++k)
      fmt::print("load case {:<16} J = {:.10e}  w J = {:.10e}{}\n", (*cases)[static_cast<int>(k)].name, e.case_values[k],
                 (*cases)[static_cast<int>(k)].weight * e.case_values[k],
                 static_cast<int>(k) == e.selected_case ? "  (selected)" : "");
  int weak_nodes = e.index_sets.num_weak_nodes();
  if (const study::ProgramHistory* history = oracle.history()) {  // every step's sets
    fmt::print("loading program: {} steps; the cost ({}) reads {}\n", history->num_steps(), history->name(),
               history->dissipation() ? std::string("every step") : fmt::format("step {}", history->cost_step() + 1));
    weak_nodes = 0;
    for (std::size_t k = 0; k < e.step_index_sets.size(); ++k) {
      fmt::print("step {}: index sets: {}\n", k + 1, e.step_index_sets[k].summary());
      weak_nodes += e.step_index_sets[k].num_weak_nodes();
    }
  }
  fmt::print("{}\n{}\n", e.contact.brief_report(), e.adjoint.brief_report());
  if (!e.ok) {
    fmt::print("error: {}\n", e.message);
    return kExitNumericalFailure;
  }
  fmt::print("index sets: {}; |L| = {:.0f}\n", e.index_sets.summary(), check.cardinality);
  if (weak_nodes > 0)
    fmt::print("note: {} weak node(s): Θ has a kink here and the difference quotients need not match ξ "
               "(compare one-sided quotients with the pieces of L instead)\n",
               weak_nodes);
  const bool uniform = check.step_scale.size() == 0 || check.step_scale.minCoeff() == check.step_scale.maxCoeff();
  if (uniform)
    fmt::print("differences with h = {:.3e} (relative step {:.1e} of {:.3e}, the width of the design's bounds)\n",
               check.step, relative_step, check.step_scale.size() ? check.step_scale(0) : 0.0);
  else
    fmt::print("differences with h_k = {:.1e} x the width of variable k's bounds (column h)\n", relative_step);
  fmt::print("{:>4} {:>18} {:>18} {:>18} {:>18} {:>10} {:>7} {:>8}{}\n", "k", "central diff.", "forward diff.",
             "backward diff.", "adjoint", "rel. error", "pieces", "verdict", uniform ? "" : "          h");
  for (std::size_t k = 0; k < check.components.size(); ++k) {
    const auto& c = check.components[k];
    fmt::print("{:>4} {:>18.10e} {:>18.10e} {:>18.10e} {:>18.10e} {:>10.2e} {:>7} {:>8}", k, c.finite_difference,
               c.forward_difference, c.backward_difference, c.adjoint, c.relative_error,
               c.piece_changes.size() + static_cast<std::size_t>(c.selected_case_changes),
               study::to_string(c.verdict));
    if (!uniform) fmt::print(" {:>10.3e}", c.step);
    fmt::print("\n");
  }
  // Which nodes change piece within ±h: at a kink the central quotient need not match ξ_k, which
  // is then one of the one-sided quotients (docs/sensitivity.md, "Verification").
  constexpr std::size_t kListed = 6;
  for (std::size_t k = 0; k < check.components.size(); ++k) {
    const auto& c = check.components[k];
    if (c.piece_changes.empty() && c.selected_case_changes == 0) continue;
    std::string nodes;
    for (std::size_t i = 0; i < std::min(kListed, c.piece_changes.size()); ++i) {
      const auto& p = c.piece_changes[i];
      nodes += fmt::format("{}node {}{} {} -> {} at {}h", i ? "; " : "", p.node,
                           p.step >= 0 ? fmt::format(" (step {})", p.step + 1) : std::string(), p.before, p.after,
                           p.side > 0 ? "+" : "-");
    }
    if (c.piece_changes.size() > kListed) nodes += fmt::format("; {} more", c.piece_changes.size() - kListed);
    if (c.selected_case_changes > 0)
      nodes += fmt::format("{}another load case attains the max on {} side(s)", nodes.empty() ? "" : "; ",
                           c.selected_case_changes);
    fmt::print("component {}: pieces change within ±h: {}\n", k, nodes);
  }
  std::size_t kinks = 0, mismatches = 0;
  for (const auto& c : check.components) {
    kinks += c.verdict == study::GradientCheck::Verdict::kKink;
    mismatches += c.verdict == study::GradientCheck::Verdict::kMismatch;
  }
  fmt::print("verdicts: {} match (error <= {:.0e} of max|ξ|), {} kink (a node changes piece within ±h and ξ_k is a "
             "one-sided quotient), {} MISMATCH (no piece change explains it)\n",
             check.components.size() - kinks - mismatches, study::kGradientCheckAgreement, kinks, mismatches);
  for (const std::string& warning : check.warnings) fmt::print("warning: {}\n", warning);
  fmt::print("largest error relative to max|ξ|: {:.2e}\n", check.worst_relative_error);
  if (const study::OrientationDesign* o = body.orientation_design())  // k = last
    fmt::print("component {} is the friction orientation s = k φ (k = {:.6e} m/rad, φ = {:.6f} deg): dΘ/dφ = "
               "{:.10e} (adjoint), {:.10e} (central difference)\n",
               alpha.size() - 1, o->scale(), o->angle(alpha(alpha.size() - 1)) * 180.0 / std::numbers::pi,
               check.components.back().adjoint * o->scale(), check.components.back().finite_difference * o->scale());
  if (e.friction_gradient.size()) {
    const auto params = sensitivity::friction_parameters(body.definition().contact->law);
    for (Eigen::Index k = 0; k < e.friction_gradient.size(); ++k)
      fmt::print("dΘ/d{} = {:.10e}\n", params.names[static_cast<std::size_t>(k)], e.friction_gradient(k));
  }
  // A component no kink explains, or a check that cannot mean anything here: the user must look.
  if (mismatches > 0 || !check.warnings.empty()) {
    fmt::print("the check needs attention (exit {}): {}\n", kExitNeedsAttention,
               mismatches > 0 ? "a difference no piece change explains" : "see the warnings above");
    return kExitNeedsAttention;
  }
  return kExitOk;
}

}  // namespace frictopt::app
