// SPDX-License-Identifier: MIT
// `frictopt check-gradient`: see apps/frictopt/commands.hpp.
#include "commands.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/design_file.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/sensitivity/friction_parameters.hpp"
#include "frictopt/study/certificate.hpp"
#include "frictopt/study/derivative_accuracy.hpp"
#include "frictopt/study/shape_optimization.hpp"
#include "frictopt/study/shape_oracle.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::app {

// frictopt check-gradient: the adjoint subgradient ξ against central differences of Θ, per
// component, with the index sets and |𝕃| at the design (spec 03 §17.1). Differences are only
// meaningful where every index set is strict; the report says when it is not.
int run_check_gradient(const std::filesystem::path& case_path, const std::filesystem::path& design_path,
                       double relative_step) {
  using namespace frictopt;
  const io::CaseDescription description = io::load_case(case_path);
  study::BodyDefinition definition = description.body;
  if (!definition.contact) throw InvalidInput(case_path.string() + ": check-gradient needs a [contact] table");
  // Finite differences need a state far more accurate than the step.
  study::tighten_for_derivatives(definition.contact->coulomb);
  study::ElasticBody body(definition);
  const Eigen::VectorXd alpha = design_path.empty() ? definition.initial_design
                                                    : io::read_design_file(design_path, definition.shape.num_controls());
  // The same admissibility check as certify: Θ and ξ are defined on Υ only.
  study::require_admissible_design(body, alpha, study::CertifyOptions{}.active_tolerance,
                                   design_path.empty() ? case_path.string() + ": design.initial" : design_path.string());
  study::ShapeOracle oracle(body, description.required_cost());
  const study::Evaluation e = oracle.evaluate_design(alpha);
  fmt::print("{}: cost {}, Θ = {:.10e}\n", case_path.string(), oracle.cost().name(), e.value);
  fmt::print("{}\n{}\n", e.contact.brief_report(), e.adjoint.brief_report());
  if (!e.ok) {
    fmt::print("error: {}\n", e.message);
    return kExitNumericalFailure;
  }
  const sensitivity::PieceEnumeration pieces = oracle.pieces(alpha, 1);
  fmt::print("index sets: {}; |L| = {:.0f}\n", e.index_sets.summary(), pieces.cardinality);
  if (e.index_sets.num_weak_nodes() > 0)
    fmt::print("note: {} weak node(s): Θ has a kink here and the difference quotients need not match ξ "
               "(compare one-sided quotients with the pieces of L instead)\n",
               e.index_sets.num_weak_nodes());
  const double h = relative_step * std::max(alpha.cwiseAbs().maxCoeff(), 1e-12);
  fmt::print("central differences with h = {:.3e} (relative step {:.1e} of max|α|)\n", h, relative_step);
  fmt::print("{:>4} {:>20} {:>20} {:>12}\n", "k", "finite difference", "adjoint", "rel. error");
  double worst = 0.0;
  const double scale = std::max(e.subgradient.cwiseAbs().maxCoeff(), 1e-300);
  for (Eigen::Index k = 0; k < alpha.size(); ++k) {
    Eigen::VectorXd a = alpha;
    a(k) += h;
    const double plus = oracle.evaluate_design(a, false).value;
    a(k) -= 2 * h;
    const double minus = oracle.evaluate_design(a, false).value;
    const double fd = (plus - minus) / (2 * h);
    // Relative to the largest component, so near-zero components do not inflate the error.
    const double error = std::abs(fd - e.subgradient(k)) / scale;
    worst = std::max(worst, error);
    fmt::print("{:>4} {:>20.10e} {:>20.10e} {:>12.2e}\n", k, fd, e.subgradient(k), error);
  }
  fmt::print("largest error relative to max|ξ|: {:.2e}\n", worst);
  if (e.friction_gradient.size()) {
    const auto params = sensitivity::friction_parameters(body.definition().contact->law);
    for (Eigen::Index k = 0; k < e.friction_gradient.size(); ++k)
      fmt::print("dΘ/d{} = {:.10e}\n", params.names[static_cast<std::size_t>(k)], e.friction_gradient(k));
  }
  return kExitOk;
}

}  // namespace frictopt::app
