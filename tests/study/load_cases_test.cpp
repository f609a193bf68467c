// SPDX-License-Identifier: MIT
// Load cases (docs/theory/load-cases.md): one case as written is the
// plain oracle bit for bit; K cases share one factorization; the weighted cost's subgradient and
// the worst case's at a strictly active case against central differences (a traction on a face
// the design moves is scaled, so the load-change term of the adjoint is exercised); at a tie of
// the worst case the one-sided directional derivatives are the max of the cases'; certify's
// generators are the union over the active cases; bad input names the field.
#include "frictopt/study/load_cases.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "common/finite_difference.hpp"
#include "common/oracle_gradient.hpp"
#include "common/invalid_case.hpp"
#include "common/case_text.hpp"
#include "common/test_bodies.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/study/certificate.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::study {
namespace {

// The thesis' 2D body with a second traction on the right face (common/test_bodies.hpp).
using frictopt::testing::two_load_body_2d;

LoadCaseDefinition load_case(std::string name, std::vector<double> load_scale, double weight = 1.0) {
  LoadCaseDefinition c;
  c.name = std::move(name);
  c.load_scale = std::move(load_scale);
  c.weight = weight;
  return c;
}

CostDefinition cost_with_cases(CaseCombination combine, std::vector<LoadCaseDefinition> cases) {
  CostDefinition d;
  d.kind = cost::CostKind::kNormalForcePower;
  d.exponent = 2.0;
  d.load_cases = LoadCasesDefinition{combine, std::move(cases)};
  return d;
}

CostDefinition plain_cost() {
  CostDefinition d;
  d.kind = cost::CostKind::kNormalForcePower;
  d.exponent = 2.0;
  return d;
}

using frictopt::testing::oracle_central_gradient;

TEST(LoadCases, OneCaseAsWrittenIsThePlainOracleBitForBit) {
  ElasticBody plain_body(two_load_body_2d()), case_body(two_load_body_2d());
  ShapeOracle plain(plain_body, plain_cost());
  ShapeOracle cased(case_body, cost_with_cases(CaseCombination::kWorst, {load_case("as written", {})}));
  const Eigen::VectorXd alpha = plain_body.definition().initial_design;
  const Evaluation a = plain.evaluate_design(alpha), b = cased.evaluate_design(alpha);
  ASSERT_TRUE(a.ok && b.ok) << a.message << b.message;
  EXPECT_EQ(a.value, b.value);
  EXPECT_EQ(b.case_values.size(), 1u);
  EXPECT_EQ(b.selected_case, 0);
  EXPECT_EQ((a.subgradient - b.subgradient).cwiseAbs().maxCoeff(), 0.0);
}

TEST(LoadCases, KCasesShareOneFactorizationPerDesign) {
  ElasticBody body(two_load_body_2d());
  ShapeOracle oracle(body, cost_with_cases(CaseCombination::kWeighted, {load_case("a", {1.0, 0.0}),
                                                                          load_case("b", {1.0, 1.0}),
                                                                          load_case("c", {0.8, 2.0})}));
  Eigen::VectorXd alpha = body.definition().initial_design;
  for (int repeat = 0; repeat < 2; ++repeat) {
    const Evaluation& e = oracle.evaluate_design(alpha);
    ASSERT_TRUE(e.ok) << e.message;
    EXPECT_EQ(e.factorizations, 1);
    EXPECT_EQ(e.case_values.size(), 3u);
    alpha(3) += 1e-3;  // another design: one more factorization, not three
  }
}

TEST(LoadCases, WeightedSubgradientMatchesCentralDifferences) {
  ElasticBody body(two_load_body_2d());
  ShapeOracle oracle(body, cost_with_cases(CaseCombination::kWeighted, {load_case("a", {1.0, 0.0}, 0.5),
                                                                          load_case("b", {1.0, 1.0}, 1.0),
                                                                          load_case("c", {0.8, 2.0}, 2.0)}));
  const Eigen::VectorXd alpha = body.definition().initial_design;
  const Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  for (int k = 0; k < 3; ++k)
    ASSERT_EQ(oracle.program(alpha, k).cost_step_index_sets().num_weak_nodes(), 0) << "case " << k << " must be strict";
  EXPECT_DOUBLE_EQ(e.value, 0.5 * e.case_values[0] + e.case_values[1] + 2.0 * e.case_values[2]);
  const Eigen::VectorXd fd = oracle_central_gradient(oracle, alpha);
  const double error = (e.subgradient - fd).norm() / fd.norm();
  std::printf("weighted: Θ = %.6e, |ξ − FD|/|FD| = %.2e (|ξ| = %.3e)\n", e.value, error, fd.norm());
  EXPECT_LE(error, 1e-5);
}

TEST(LoadCases, TheLoadChangeTermIsNeeded) {
  // The right traction's load changes with α: without the term −∇_α[ψᵀ(l_k − l)] the ξ of a case
  // that scales it would differ from central differences (a test that can fail).
  ElasticBody body(two_load_body_2d());
  ShapeOracle oracle(body, cost_with_cases(CaseCombination::kWorst, {load_case("c", {0.8, 2.0})}));
  const Eigen::VectorXd alpha = body.definition().initial_design;
  const Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  const auto results = oracle.program(alpha, 0).cost_step_subgradients({sensitivity::default_piece(e.index_sets)});
  Eigen::VectorXd psi = Eigen::VectorXd::Zero(body.mesh().num_dofs());
  const auto& dofs = body.elasticity().dofs();
  for (int k = 0; k < dofs.num_free(); ++k) psi(dofs.free_dofs()[static_cast<std::size_t>(k)]) = results[0].psi_u(k);
  const Eigen::VectorXd term = oracle.load_cases()->load_change_shape_derivative(0, oracle.last_state().positions, psi);
  const Eigen::VectorXd fd = oracle_central_gradient(oracle, alpha);
  EXPECT_LE((e.subgradient - fd).norm() / fd.norm(), 1e-5);
  EXPECT_GT((e.subgradient - term - fd).norm() / fd.norm(), 1e-4) << "the term is not negligible here";
}

TEST(LoadCases, WorstCaseAtAStrictlyActiveCaseIsThatCasesSubgradient) {
  ElasticBody body(two_load_body_2d()), single_body(two_load_body_2d());
  ShapeOracle oracle(body, cost_with_cases(CaseCombination::kWorst, {load_case("a", {1.0, 0.0}),
                                                                       load_case("c", {0.8, 2.0}),
                                                                       load_case("b", {1.0, 1.0})}));
  const Eigen::VectorXd alpha = body.definition().initial_design;
  const Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  const int s = e.selected_case;
  std::printf("worst: J = (%.6e, %.6e, %.6e), selected %d\n", e.case_values[0], e.case_values[1], e.case_values[2], s);
  for (int k = 0; k < 3; ++k)
    if (k != s) {
      ASSERT_LT(e.case_values[static_cast<std::size_t>(k)], 0.99 * e.value) << "strictly active";
    }
  // The selected case alone, as a one-case study: the same ξ.
  ShapeOracle single(single_body, cost_with_cases(CaseCombination::kWorst,
                                                  {oracle.load_cases()->definition().cases[static_cast<std::size_t>(s)]}));
  const Evaluation one = single.evaluate_design(alpha);
  ASSERT_TRUE(one.ok) << one.message;
  EXPECT_NEAR(one.value, e.value, 1e-12 * e.value);
  EXPECT_LE((one.subgradient - e.subgradient).norm(), 1e-8 * e.subgradient.norm());
  const Eigen::VectorXd fd = oracle_central_gradient(oracle, alpha);
  const double error = (e.subgradient - fd).norm() / fd.norm();
  std::printf("worst, strictly active: |ξ − FD|/|FD| = %.2e\n", error);
  EXPECT_LE(error, 1e-5);
}

// The optimizer's cuts of the other cases (Evaluation::case_cuts, docs/theory/load-cases.md §2):
// for every case k ≠ s with w_k > 0, (w_k J_k, w_k ξ_k) — checked against each case solved alone
// as a one-case study (an independent oracle), and passed on as optim::OracleResult::pieces.
TEST(LoadCases, WorstCaseReturnsTheOtherCasesCutsForTheOptimizer) {
  const std::vector<LoadCaseDefinition> cases = {load_case("a", {1.0, 0.0}, 1.0), load_case("c", {0.8, 2.0}, 0.5),
                                                 load_case("b", {1.0, 1.0}, 2.0), load_case("off", {1.0, 0.5}, 0.0)};
  ElasticBody body(two_load_body_2d());
  ShapeOracle oracle(body, cost_with_cases(CaseCombination::kWorst, cases));
  const Eigen::VectorXd alpha = body.definition().initial_design;
  const Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  const int s = e.selected_case;
  ASSERT_EQ(e.case_cuts.size(), 2u) << "one cut per other case with a positive weight";
  std::size_t cut = 0;
  for (int k = 0; k < 3; ++k) {
    if (k == s) continue;
    const double w = cases[static_cast<std::size_t>(k)].weight;
    ElasticBody alone_body(two_load_body_2d());
    LoadCaseDefinition unweighted = cases[static_cast<std::size_t>(k)];
    unweighted.weight = 1.0;
    ShapeOracle alone(alone_body, cost_with_cases(CaseCombination::kWorst, {unweighted}));
    const Evaluation one = alone.evaluate_design(alpha);
    ASSERT_TRUE(one.ok) << one.message;
    const optim::PieceCut& c = e.case_cuts[cut++];
    EXPECT_NEAR(c.value, w * one.value, 1e-12 * w * one.value) << "case " << k;
    EXPECT_LE((c.subgradient - w * one.subgradient).norm(), 1e-8 * w * one.subgradient.norm()) << "case " << k;
    EXPECT_LE(c.value, e.value);
  }
  // The optim::Oracle answer carries them as the pieces of the max.
  const optim::OracleResult r = oracle.evaluate(alpha);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.pieces.size(), 2u);
  // Off on request, and never for the weighted sum (not a max).
  ElasticBody off_body(two_load_body_2d()), sum_body(two_load_body_2d());
  ShapeOracle off(off_body, cost_with_cases(CaseCombination::kWorst, cases));
  off.set_case_cuts(false);
  const Evaluation e_off = off.evaluate_design(alpha);
  ASSERT_TRUE(e_off.ok) << e_off.message;
  EXPECT_TRUE(e_off.case_cuts.empty());
  EXPECT_EQ(e_off.value, e.value);
  EXPECT_EQ(e_off.subgradient, e.subgradient);
  ShapeOracle sum(sum_body, cost_with_cases(CaseCombination::kWeighted, cases));
  const Evaluation e_sum = sum.evaluate_design(alpha);
  ASSERT_TRUE(e_sum.ok) << e_sum.message;
  EXPECT_TRUE(e_sum.case_cuts.empty());
}

TEST(LoadCases, AtATieTheOneSidedDerivativesAreTheMaxOfTheCases) {
  // Weights that make w_a J_a = w_c J_c at α exactly (up to rounding): Θ = max is at a kink, and
  // for every direction h, Θ'(α; h) = max(w_a ξ_a·h, w_c ξ_c·h) (docs/theory/load-cases.md).
  ElasticBody probe_body(two_load_body_2d());
  ShapeOracle probe(probe_body, cost_with_cases(CaseCombination::kWeighted, {load_case("a", {1.0, 0.0}),
                                                                               load_case("c", {0.8, 2.0})}));
  const Eigen::VectorXd alpha = probe_body.definition().initial_design;
  const Evaluation p = probe.evaluate_design(alpha, false);
  ASSERT_TRUE(p.ok) << p.message;
  const double w_c = p.case_values[0] / p.case_values[1];
  const auto xi = probe.program(alpha, 0).cost_step_subgradients({sensitivity::default_piece(probe.program(alpha, 0).cost_step_index_sets())});
  const auto xc = probe.program(alpha, 1).cost_step_subgradients({sensitivity::default_piece(probe.program(alpha, 1).cost_step_index_sets())});
  const Eigen::VectorXd xi_a = xi[0].subgradient, xi_c = w_c * xc[0].subgradient;

  ElasticBody body(two_load_body_2d());
  ShapeOracle oracle(body, cost_with_cases(CaseCombination::kWorst, {load_case("a", {1.0, 0.0}, 1.0),
                                                                       load_case("c", {0.8, 2.0}, w_c)}));
  const Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_NEAR(e.case_values[0], w_c * e.case_values[1], 1e-12 * e.value) << "a tie";
  // A direction that separates the cases' slopes (the difference of the two subgradients, minus
  // its mean to stay on the volume constraint), and the opposite one.
  Eigen::VectorXd h = xi_a - xi_c;
  h.array() -= h.mean();
  h /= h.norm();
  const double step = 1e-4 * alpha.cwiseAbs().maxCoeff();
  for (double sign : {1.0, -1.0}) {
    const Eigen::VectorXd d = sign * h;
    // One-sided, second order: Richardson on forward differences with steps t and t/2.
    const auto forward = [&](double t) { return (oracle.evaluate_design(alpha + t * d, false).value - e.value) / t; };
    const double derivative = 2.0 * forward(step / 2) - forward(step);
    const double expected = std::max(xi_a.dot(d), xi_c.dot(d));
    std::printf("tie, sign %+g: one-sided %.8e, max(ξ_a·h, ξ_c·h) = %.8e (ξ_a·h %.8e, ξ_c·h %.8e)\n", sign, derivative,
                expected, xi_a.dot(d), xi_c.dot(d));
    EXPECT_NEAR(derivative, expected, 1e-5 * std::max(std::abs(xi_a.dot(d)), std::abs(xi_c.dot(d))));
    // A kink indeed: the two slopes differ by much more than the tolerance.
    EXPECT_GT(std::abs(xi_a.dot(d) - xi_c.dot(d)), 1e-2 * std::abs(expected));
  }
  // certify: both cases active, the generators are the union of their pieces.
  CertifyOptions options;
  options.clarke_only = true;
  const Certificate c = certify(oracle, alpha, options);
  ASSERT_EQ(c.status, Status::kConverged) << c.message;
  std::printf("%s", c.report().c_str());
  ASSERT_EQ(c.load_cases.size(), 2u);
  EXPECT_TRUE(c.load_cases[0].active && c.load_cases[1].active);
  ASSERT_EQ(c.subgradients.cols(), 2);
  EXPECT_LE((c.subgradients.col(0) - xi_a).norm(), 1e-8 * xi_a.norm());
  EXPECT_LE((c.subgradients.col(1) - xi_c).norm(), 1e-8 * xi_c.norm());
}

TEST(LoadCases, WeightedCertificateSumsOnePiecePerCase) {
  // At a point strict in every case, 𝕃_k = {default}: the generators of Σ_k w_k ∂J_k are the one
  // sum Σ_k w_k ξ_k, which is the oracle's ξ; every case is active.
  ElasticBody body(two_load_body_2d());
  ShapeOracle oracle(body, cost_with_cases(CaseCombination::kWeighted, {load_case("a", {1.0, 0.0}, 0.5),
                                                                          load_case("b", {1.0, 1.0}, 1.0),
                                                                          load_case("zero", {0.8, 2.0}, 0.0)}));
  const Eigen::VectorXd alpha = body.definition().initial_design;
  const Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  const Certificate c = certify(oracle, alpha);
  ASSERT_EQ(c.status, Status::kConverged) << c.message;
  std::printf("%s", c.report().c_str());
  ASSERT_EQ(c.load_cases.size(), 3u);
  EXPECT_TRUE(c.load_cases[0].active && c.load_cases[1].active);
  EXPECT_FALSE(c.load_cases[2].active) << "a zero weight drops the case";
  EXPECT_EQ(c.combine, "weighted");
  ASSERT_EQ(c.subgradients.cols(), 1);
  EXPECT_LE((c.subgradients.col(0) - e.subgradient).norm(), 1e-10 * e.subgradient.norm());
  EXPECT_DOUBLE_EQ(e.value, 0.5 * e.case_values[0] + e.case_values[1]);
  // (MF1′) per active case at its own state: a strict point, full row rank.
  EXPECT_TRUE(c.load_cases[0].mf1.computed && c.load_cases[0].mf1.full_row_rank);
  EXPECT_TRUE(c.load_cases[1].mf1.computed && c.load_cases[1].mf1.full_row_rank);
  EXPECT_FALSE(c.load_cases[2].mf1.computed);
}

// ---------------------------------------------------------------------------------------------
// Bad input (item 6): each an InvalidInput naming the field.

std::string block_case(const std::string& extra) {
  return frictopt::testing::pushed_block_3d() + "[cost]\nkind = \"pressure_norm\"\n" + extra;
}

TEST(LoadCasesInput, ValidCasesParse) {
  const io::CaseDescription c = io::parse_case(block_case(R"(
[study]
combine = "weighted"
cases = ["pull", "press"]
[[load_case]]
name = "press"
load_scale = [0.0]
[[load_case]]
name = "pull"
load_scale = [2.0]
dirichlet_scale = [0.5]
weight = 3.0
[[load_case]]
name = "unused"
)"),
                                               "ok.toml");
  ASSERT_TRUE(c.cost && c.cost->load_cases);
  const LoadCasesDefinition& d = *c.cost->load_cases;
  EXPECT_EQ(d.combine, CaseCombination::kWeighted);
  ASSERT_EQ(d.cases.size(), 2u);
  EXPECT_EQ(d.cases[0].name, "pull");  // the order of [study] cases
  EXPECT_EQ(d.cases[0].weight, 3.0);
  EXPECT_EQ(d.cases[1].load_scale, std::vector<double>{0.0});
  EXPECT_EQ(c.problem_settings.count("load_case[1].weight"), 1u) << "the fingerprint of a run sees the cases";
}

TEST(LoadCasesInput, BadInputNamesTheField) {
  using frictopt::testing::expect_invalid_case;
  const std::string a = "[[load_case]]\nname = \"a\"\n";
  expect_invalid_case(block_case(a + "weight = -1.0\n"), {"load_case[0].weight", "-1", ">= 0"});
  expect_invalid_case(block_case(a + "weight = 0.0\n[[load_case]]\nname = \"b\"\nweight = 0\n"),
                      {"load_case.weight", "all 2 weights are 0"});
  expect_invalid_case(block_case(a + "[[load_case]]\nname = \"a\"\n"), {"load_case[1].name", "\"a\"", "unique"});
  expect_invalid_case(block_case(a + "[study]\ncases = [\"a\", \"b\"]\n"), {"study.cases[1]", "\"b\"", "one of \"a\""});
  expect_invalid_case(block_case(a + "[study]\ncombine = \"mean\"\n"), {"study.combine", "worst, weighted"});
  expect_invalid_case(block_case(a + "load_scale = [1.0, 2.0]\n"),
                      {"load_case[0].load_scale has 2 entries, but the case has 1 [[load]] table"});
  expect_invalid_case(block_case("[study]\ncombine = \"worst\"\n"), {"load_case is missing"});
  expect_invalid_case(block_case(a + "nmae = \"x\"\n"), {"load_case[0]", "nmae"});
}

TEST(LoadCasesInput, ComplianceWithLoadCasesIsRefused) {
  io::CaseDescription c = io::parse_case(block_case("[[load_case]]\nname = \"a\"\n"), "ok.toml");
  c.cost->kind = cost::CostKind::kCompliance;
  ElasticBody body(c.body);
  try {
    ShapeOracle oracle(body, *c.cost);
    ADD_FAILURE() << "compliance with load cases accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("compliance"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace frictopt::study
