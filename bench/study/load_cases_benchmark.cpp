// SPDX-License-Identifier: MIT
// Load cases (docs/benchmarks.md §2c): the time of one oracle evaluation with K = 1, 2, 4, 8 load cases
// on the demo's mesh against its floor, one factorization + K contact solves + K adjoints (each
// part timed on its own at the same design), and a K = 8 worst-case optimization against the
// single-load one. The body, law and loads are cases3d/grip-worst-case: the demo's block under
// the anisotropic 4-gon, pressed, then dragged 0.1 mm in K directions θ_k = 2πk/K.
//   build/bench/study/load_cases_benchmark            (evaluations: K = 1, 2, 4, 8)
//   build/bench/study/load_cases_benchmark --study    (also the optimizations: K = 1, K = 8 with and
//                                                      without the other cases' cuts; minutes)
#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "common/timing.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/sensitivity/piece.hpp"
#include "frictopt/study/shape_optimization.hpp"

namespace {

using namespace frictopt;
using frictopt::bench::Clock;
using frictopt::bench::median;
using frictopt::bench::seconds;

// The grip case's cost with K drag directions θ_k = 2πk/K (dirichlet_scale = [press, cos, sin]).
study::CostDefinition with_directions(study::CostDefinition cost, int K, study::CaseCombination combine) {
  study::LoadCasesDefinition cases;
  cases.combine = combine;
  for (int k = 0; k < K; ++k) {
    const double theta = 2.0 * std::numbers::pi * k / K;
    study::LoadCaseDefinition c;
    c.name = fmt::format("drag {:.0f}", theta * 180.0 / std::numbers::pi);
    c.dirichlet_scale = {1.0, std::cos(theta), std::sin(theta)};
    cases.cases.push_back(c);
  }
  cost.load_cases = cases;
  return cost;
}

// Designs near α⁰ (a fresh one per evaluation, so that no cache answers): α⁰ + small
// volume-neutral perturbations inside Υ.
std::vector<Eigen::VectorXd> designs(const Eigen::VectorXd& alpha0, int n) {
  std::mt19937_64 rng(20261125);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::VectorXd> out;
  for (int r = 0; r < n; ++r) {
    Eigen::VectorXd h(alpha0.size());
    for (Eigen::Index i = 0; i < h.size(); ++i) h(i) = u(rng);
    h.array() -= h.mean();
    out.push_back(alpha0 + 2e-5 * h / h.cwiseAbs().maxCoeff());
  }
  return out;
}

struct Row {
  int K = 0;
  double evaluation = 0, factorization = 0, contact = 0, adjoints = 0, worst_evaluation = 0, cuts_evaluation = 0;
  int factorizations = 0;
};

Row time_evaluations(const io::CaseDescription& description, int K, int repeats) {
  Row row;
  row.K = K;
  std::vector<double> eval_s, worst_s, cuts_s, fact_s, contact_s, adjoint_s;
  study::ElasticBody body(description.body), worst_body(description.body), cuts_body(description.body);
  study::ShapeOracle weighted(body, with_directions(*description.cost, K, study::CaseCombination::kWeighted));
  // The worst case with one adjoint (the selected case's), and with the other cases' cuts for
  // the optimizer (K adjoints; the default in study::optimize).
  study::ShapeOracle worst(worst_body, with_directions(*description.cost, K, study::CaseCombination::kWorst));
  worst.set_case_cuts(false);
  study::ShapeOracle cuts(cuts_body, with_directions(*description.cost, K, study::CaseCombination::kWorst));
  const auto alphas = designs(description.body.initial_design, repeats + 1);
  // Warm-up at α⁰ (first symbolic analysis, first cold contact solves).
  (void)weighted.evaluate_design(description.body.initial_design);
  (void)worst.evaluate_design(description.body.initial_design);
  (void)cuts.evaluate_design(description.body.initial_design);
  for (int r = 0; r < repeats; ++r) {
    const Eigen::VectorXd& alpha = alphas[static_cast<std::size_t>(r)];
    // Θ and ξ with K adjoints ("weighted"), and with one ("worst").
    auto t0 = Clock::now();
    const study::Evaluation& e = weighted.evaluate_design(alpha);
    eval_s.push_back(seconds(t0, Clock::now()));
    if (!e.ok) throw NumericalFailure(e.message);
    row.factorizations = e.factorizations;
    t0 = Clock::now();
    const study::Evaluation& w = worst.evaluate_design(alpha);
    worst_s.push_back(seconds(t0, Clock::now()));
    if (!w.ok) throw NumericalFailure(w.message);
    t0 = Clock::now();
    const study::Evaluation& c = cuts.evaluate_design(alpha);
    cuts_s.push_back(seconds(t0, Clock::now()));
    if (!c.ok) throw NumericalFailure(c.message);
    // The floor's parts at the same α: the factorization (with assembly) of case 0, the K
    // contact solves as the solver reports them, and K adjoints timed one by one.
    const study::BodyState& s0 = *weighted.program(alpha, 0).cost_state();
    fact_s.push_back(s0.summary.assembly_seconds + s0.summary.factorization_seconds);
    double contact = 0, adjoints = 0;
    for (int k = 0; k < K; ++k) {
      contact += weighted.program(alpha, k).cost_state()->contact->summary.time_seconds;
      const auto piece = sensitivity::default_piece(weighted.program(alpha, k).cost_step_index_sets());
      t0 = Clock::now();
      const auto result = weighted.program(alpha, k).cost_step_subgradients({piece});
      adjoints += seconds(t0, Clock::now());
      if (result[0].summary.status != Status::kConverged) throw NumericalFailure(result[0].summary.message);
    }
    contact_s.push_back(contact);
    adjoint_s.push_back(adjoints);
  }
  row.evaluation = median(eval_s);
  row.worst_evaluation = median(worst_s);
  row.cuts_evaluation = median(cuts_s);
  row.factorization = median(fact_s);
  row.contact = median(contact_s);
  row.adjoints = median(adjoint_s);
  return row;
}

struct StudyRow {
  int K = 0;
  double seconds = 0;
  int iterations = 0, evaluations = 0;
  double value = 0;
  std::string status;
};

StudyRow time_study(const io::CaseDescription& description, int K, bool case_cuts) {
  study::ElasticBody body(description.body);
  study::ShapeOracle oracle(body, with_directions(*description.cost, K, study::CaseCombination::kWorst));
  optim::BundleTrust::Options options = description.optimization;
  options.use_piece_cuts = case_cuts;
  const auto t0 = Clock::now();
  const optim::BundleTrust::Summary s = study::optimize(oracle, options, {});
  StudyRow row;
  row.K = K;
  row.seconds = seconds(t0, Clock::now());
  row.iterations = s.iterations;
  row.evaluations = s.evaluations;
  row.value = s.f;
  row.status = std::string(to_string(s.status));
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  const bool with_study = argc > 1 && std::strcmp(argv[1], "--study") == 0;
  const io::CaseDescription description = io::load_case(FRICTOPT_SOURCE_DIR "/cases3d/grip-worst-case/case.toml");
  constexpr int kRepeats = 5;
  fmt::print("load cases on the demo's mesh (16 x 16 x 8, 289 contact nodes); medians of {} evaluations at "
             "fresh designs\n",
             kRepeats);
  fmt::print("{:>3} {:>12} {:>10} {:>10} {:>10} {:>12} {:>8} {:>14} {:>14} {:>7}\n", "K", "eval (K adj)", "factor.",
             "K contact", "K adjoint", "floor", "ratio", "worst (1 adj)", "worst + cuts", "factor");
  for (int K : {1, 2, 4, 8}) {
    const Row r = time_evaluations(description, K, kRepeats);
    const double floor = r.factorization + r.contact + r.adjoints;
    fmt::print("{:>3} {:>11.3f}s {:>9.3f}s {:>9.3f}s {:>9.3f}s {:>11.3f}s {:>8.2f} {:>13.3f}s {:>13.3f}s {:>7}\n", r.K,
               r.evaluation, r.factorization, r.contact, r.adjoints, floor, r.evaluation / floor, r.worst_evaluation,
               r.cuts_evaluation, r.factorizations);
  }
  fmt::print("peak resident memory {:.0f} MB\n", frictopt::bench::peak_rss_megabytes());
  if (!with_study) return 0;
  fmt::print("\nworst-case optimization (the case's [optimization] options), K = 1 vs K = 8\n");
  const StudyRow one = time_study(description, 1, true);
  const StudyRow eight = time_study(description, 8, true);
  // The same K = 8 study with the selected case's subgradient only ([optimization] case_cuts = false).
  const StudyRow plain = time_study(description, 8, false);
  for (const auto& [r, label] : {std::pair{one, ""}, std::pair{eight, ", case cuts"}, std::pair{plain, ", no case cuts"}})
    fmt::print("K = {}{}: {:.1f} s, {} iterations, {} evaluations, Θ = {:.6e}, {}\n", r.K, label, r.seconds,
               r.iterations, r.evaluations, r.value, r.status);
  for (const auto& [r, label] : {std::pair{eight, "case cuts (default)"}, std::pair{plain, "no case cuts"}})
    fmt::print("time ratio K = 8 / K = 1, {}: {:.2f} (per evaluation {:.2f})\n", label, r.seconds / one.seconds,
               (r.seconds / r.evaluations) / (one.seconds / one.evaluations));
  return 0;
}
