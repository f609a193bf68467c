// SPDX-License-Identifier: MIT
// Prints the Markdown table of docs/optim-testset.md: every Lukšan–Vlček problem and scaled
// variant solved by BundleTrust with DEFAULT options (only keep_history is switched off), and
// the median evaluation count. Exit code 0 iff every problem is solved to the accuracy and no
// run reports "converged" at an inaccurate value.
//   optim_testset_table [--epsilon E] [--accuracy A] [--confirm] [--no-units-check] [--units-spread S]
//                       [--metric [--metric-ratio K]
//                       [--metric-memory M] [--metric-damping W]] [--pieces] [--baseline] [--only NAME] > table.md
// --epsilon sets BundleTrust::Options::epsilon (default: the default, 1e-4) and --accuracy the
// relative accuracy checked (default: 1e-4). --confirm passes every "converged" through
// confirm_in_point_units (point_units_check.hpp; evaluations include it), whatever the units'
// spread; --no-units-check switches off BundleTrust's default confirmation of stops whose units
// spread by more than Options::point_units_spread (the method before that confirmation), and
// --units-spread S sets that threshold. --metric switches on
// BundleTrust::Options::variable_metric (--metric-ratio, --metric-memory, --metric-damping set its
// bound, memory and damping). --baseline adds the projected subgradient method
// with 10 000 evaluations. --pieces gives the minimax problems of TEST22 their structured oracle
// (LuksanVlcekProblem::evaluate_with_pieces: the cut of every piece at every point), the others
// keep theirs. --only runs one problem and prints its brief report on stderr;
// with --only, the final point is also checked by gradient sampling (Burke–Lewis–Overton): the
// certificate of g(x) and 4n fresh subgradients at uniform points of the ball B(x, r), for
// r = 1e-2, 1e-4, 1e-6, 1e-8 times max(1, ‖x‖), relative to the largest of them (stderr); and,
// for a minimax problem, the exact Clarke certificate at x: dist(0, conv{∇f_k : f_k >= f − τ}
// + N(x)) over the pieces within τ = 1e-10, 1e-8, 1e-6, 1e-4 times max(1, |f|) of the max.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "frictopt/optim/bundle_trust.hpp"
#include "testset/luksan_vlcek.hpp"
#include "frictopt/optim/point_units_check.hpp"
#include "frictopt/optim/projected_subgradient.hpp"
#include "frictopt/optim/stationarity.hpp"

#include <Eigen/Core>
#include <random>

namespace fo = frictopt::optim;

int main(int argc, char** argv) {
  double accuracy = 1e-4;  // the report's |f − f*| <= 1e-4·max(1, |f*|)
  bool baseline = false;
  bool confirm = false;
  bool pieces = false;
  std::string only;
  fo::BundleTrust::Options bt;
  bt.keep_history = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--epsilon" && i + 1 < argc) bt.epsilon = std::atof(argv[++i]);
    else if (a == "--accuracy" && i + 1 < argc) accuracy = std::atof(argv[++i]);
    else if (a == "--baseline") baseline = true;
    else if (a == "--confirm") confirm = true;
    else if (a == "--no-units-check") bt.confirm_in_point_units = false;
    else if (a == "--units-spread" && i + 1 < argc) bt.point_units_spread = std::atof(argv[++i]);
    else if (a == "--metric") bt.variable_metric = true;
    else if (a == "--metric-ratio" && i + 1 < argc) bt.metric_ratio_bound = std::atof(argv[++i]);
    else if (a == "--metric-memory" && i + 1 < argc) bt.metric_memory = std::atoi(argv[++i]);
    else if (a == "--metric-damping" && i + 1 < argc) bt.metric_damping = std::atof(argv[++i]);
    else if (a == "--only" && i + 1 < argc) only = argv[++i];
    else if (a == "--pieces") pieces = true;
    else {
      std::fprintf(stderr, "usage: %s [--epsilon E] [--accuracy A] [--confirm] [--no-units-check] [--units-spread S] [--metric] [--metric-ratio K] [--metric-memory M] [--metric-damping W] [--pieces] [--baseline] [--only NAME]\n", argv[0]);
      return 2;
    }
  }
  std::vector<fo::LuksanVlcekProblem> problems = fo::luksan_vlcek_unconstrained();
  for (auto set : {fo::luksan_vlcek_constrained(), fo::luksan_vlcek_scaled_variants()})
    problems.insert(problems.end(), set.begin(), set.end());

  std::printf("| problem | set | n | f* | f found | rel. error | evals | iters | status |%s\n",
              baseline ? " PSG rel. error |" : "");
  std::printf("|---|---|---:|---:|---:|---:|---:|---:|---|%s\n", baseline ? "---:|" : "");
  int solved = 0, total = 0, false_converged = 0;
  std::vector<int> evals, evals_original;
  for (const auto& p : problems) {
    if (!only.empty() && p.name != only) continue;
    fo::FunctionOracle oracle(pieces && p.evaluate_with_pieces ? p.evaluate_with_pieces : p.evaluate);
    auto s = fo::BundleTrust(bt, p.constraints).minimize(oracle, p.x0);
    if (confirm) s = fo::confirm_in_point_units(bt, p.constraints, oracle, p.x0, std::move(s));
    const bool ok = p.solved(s.f, accuracy);
    solved += ok;
    false_converged += s.converged() && !ok;
    ++total;
    evals.push_back(s.evaluations);
    if (p.value_unit == 1.0 && p.name.find('*') == std::string::npos) evals_original.push_back(s.evaluations);
    std::printf("| %s | %s | %ld | %.8g | %.8g | %.1e%s | %d | %d | %s%s |", p.name.c_str(), p.source.c_str(),
                static_cast<long>(p.dimension()), p.f_star, s.f, p.relative_error(s.f), ok ? "" : " **no**",
                s.evaluations, s.iterations, std::string(frictopt::to_string(s.status)).c_str(),
                s.converged() ? "" : (" (" + std::string(fo::to_string(s.stop_reason)) + ")").c_str());
    if (baseline) {
      fo::ProjectedSubgradient::Options po;
      po.max_evaluations = 10000;
      fo::FunctionOracle oracle2(p.evaluate);
      const auto b = fo::ProjectedSubgradient(po, p.constraints).minimize(oracle2, p.x0);
      std::printf(" %.1e |", p.relative_error(b.f));
    }
    std::printf("\n");
    if (!only.empty()) {
      std::fprintf(stderr, "%s\n", s.brief_report().c_str());
      std::mt19937 rng(1);
      std::normal_distribution<double> normal;
      std::uniform_real_distribution<double> uniform;
      const Eigen::Index n = s.x.size();
      for (double r : {1e-2, 1e-4, 1e-6, 1e-8}) {
        const double radius = r * std::max(1.0, s.x.norm());
        Eigen::MatrixXd Xi(n, 4 * n + 1);
        Xi.col(0) = p.evaluate(s.x).subgradient;
        for (Eigen::Index j = 1; j < Xi.cols(); ++j) {
          Eigen::VectorXd u(n);
          for (Eigen::Index i = 0; i < n; ++i) u(i) = normal(rng);
          u *= radius * std::pow(uniform(rng), 1.0 / static_cast<double>(n)) / u.norm();
          Eigen::VectorXd y = s.x + u;
          // Keep the sample feasible: a point outside Υ has no normal cone of x's.
          if (p.constraints.max_violation(y) > 0.0) y = s.x;
          Xi.col(j) = p.evaluate(y).subgradient;
        }
        const auto c = fo::stationarity_certificate(Xi, s.x, p.constraints);
        std::fprintf(stderr, "gradient sampling r = %.0e: delta = %.3e, max|g| = %.3e, delta/max|g| = %.2e\n", r,
                     c.distance, c.subgradient_scale, c.distance / c.subgradient_scale);
      }
      if (p.evaluate_with_pieces) {
        const fo::OracleResult at = p.evaluate_with_pieces(s.x);
        for (double tau : {1e-10, 1e-8, 1e-6, 1e-4}) {
          const double gap = tau * std::max(1.0, std::abs(at.value));
          std::vector<Eigen::VectorXd> active{at.subgradient};
          for (const fo::PieceCut& piece : at.pieces)
            if (piece.value >= at.value - gap) active.push_back(piece.subgradient);
          Eigen::MatrixXd Xi(n, static_cast<Eigen::Index>(active.size()));
          for (std::size_t j = 0; j < active.size(); ++j) Xi.col(static_cast<Eigen::Index>(j)) = active[j];
          const auto c = fo::stationarity_certificate(Xi, s.x, p.constraints);
          std::fprintf(stderr, "Clarke certificate of the pieces within %.0e of the max: %zu pieces, delta = %.3e, max|g| = %.3e, delta/max|g| = %.2e\n",
                       gap, active.size(), c.distance, c.subgradient_scale, c.distance / c.subgradient_scale);
        }
      }
    }
  }
  auto median = [](std::vector<int> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
  };
  int sum = 0;
  for (int e : evals) sum += e;
  std::printf("\nepsilon = %g, accuracy %g: solved %d of %d; %d runs reported converged at an inaccurate "
              "value; evaluations: median %.1f over all runs, median %.1f over the %zu original problems, "
              "total %d.\n",
              bt.epsilon, accuracy, solved, total, false_converged, median(evals), median(evals_original),
              evals_original.size(), sum);
  return solved == total && false_converged == 0 ? 0 : 1;
}
