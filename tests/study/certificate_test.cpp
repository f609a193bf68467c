// SPDX-License-Identifier: MIT
// study::certify (thesis §5.3; docs/theory/stationarity.md): the distance at a strict point
// against its closed form, |𝕃| and the (MF1′) matrix at a constructed weak point, and the
// distance falling along a short optimization run.
#include "frictopt/study/certificate.hpp"

#include <gtest/gtest.h>

#include "common/test_bodies.hpp"

#include <cstdio>

#include "frictopt/core/error.hpp"
#include "frictopt/cost/cost_functional.hpp"
#include "frictopt/sensitivity/piece.hpp"
#include "frictopt/study/shape_optimization.hpp"

namespace frictopt::study {
namespace {

// The thesis' 2D body (docs/theory/examples.md §1) on a coarse mesh with tight solver tolerances,
// and the volume equality Σα = 0.75 (C2 = 1.9 with a = 2, C4 = 1, d = 15: Σα = d(C4 − C2/a)), which
// the initial design α = 0.05 satisfies.
BodyDefinition thesis_body_2d(int n1, int nv) {
  return frictopt::testing::thesis_body_2d(contact::FrictionLaw::interval(0.25, 0.25), n1, nv);
}

TEST(Certify, StrictPointHasOnePieceAndTheClosedFormDistance) {
  ElasticBody body(thesis_body_2d(20, 8));
  ShapeOracle oracle(body, cost::make_compliance());
  const Eigen::VectorXd alpha = body.definition().initial_design;
  const Certificate c = certify(oracle, alpha);
  ASSERT_EQ(c.status, Status::kConverged) << c.message;
  std::printf("%s", c.report().c_str());
  ASSERT_EQ(c.index_sets.num_weak_nodes(), 0) << c.index_sets.summary();
  EXPECT_EQ(c.cardinality, 1.0);
  EXPECT_FALSE(c.sampled);
  ASSERT_EQ(c.subgradients.cols(), 1);
  const Eigen::VectorXd xi = c.subgradients.col(0);
  EXPECT_TRUE(xi.isApprox(oracle.evaluate_design(alpha).subgradient, 1e-12));
  // Only the volume equality is active (0 < α < C0, equal neighbours): N_Υ = span{1}, so the
  // distance is ‖ξ − mean(ξ)·1‖, and the certificate's parts add up to it.
  EXPECT_EQ(c.active_constraints.size(), 1u);
  const double expected = (xi.array() - xi.mean()).matrix().norm();
  EXPECT_NEAR(c.clarke.distance, expected, 1e-8 * xi.norm());
  EXPECT_NEAR(c.clarke.distance, (xi + c.clarke.normal_part).norm(), 1e-10 * xi.norm());
  EXPECT_DOUBLE_EQ(c.default_piece.distance, c.clarke.distance);  // one piece: the same QP
  EXPECT_NEAR(c.relative_distance, expected / xi.norm(), 1e-8);
  // Strict point: no extra conditions, (MF1′) is the piece's own system, which is nonsingular.
  ASSERT_TRUE(c.mf1.computed);
  const auto p = body.contact_boundary()->num_nodes();
  EXPECT_EQ(c.mf1.extra_conditions, 0);
  EXPECT_EQ(c.mf1.rows, 2 * p);
  EXPECT_EQ(c.mf1.cols, 15 + 2 * p);
  EXPECT_TRUE(c.mf1.full_row_rank);
  // One generator is its own extreme point: δ_M = δ, and the thesis criterion holds.
  ASSERT_TRUE(c.mordukhovich.computed) << c.mordukhovich.message;
  EXPECT_EQ(c.mordukhovich.extreme.size(), 1u);
  EXPECT_NEAR(c.mordukhovich.distance, c.clarke.distance, 1e-10 * xi.norm());
  EXPECT_TRUE(c.mordukhovich.clarke_minimizer_is_extreme);
}

// Zero load and zero gaps: every contact node touches without force (I₀ with u_t = 0, rule R2),
// as in tests/sensitivity/adjoint_test.cpp (weak_contact_body).
TEST(Certify, WeakPointEnumeratesLAndReportsTheMf1Rank) {
  BodyDefinition definition = thesis_body_2d(3, 2);
  definition.tractions.clear();
  definition.admissible.volume.reset();
  definition.initial_design = Eigen::VectorXd::Zero(15);
  ElasticBody body(definition);
  const auto p = body.contact_boundary()->num_nodes();
  ShapeOracle oracle(body, cost::make_target_normal_force(Eigen::VectorXd::LinSpaced(p, 1e6, 2e6)));
  const Eigen::VectorXd alpha = definition.initial_design;
  const Certificate c = certify(oracle, alpha);
  ASSERT_EQ(c.status, Status::kConverged) << c.message;
  std::printf("%s", c.report().c_str());
  EXPECT_EQ(c.index_sets.count(sensitivity::NormalSet::kWeakContact), p) << c.index_sets.summary();
  EXPECT_FALSE(c.sampled);
  EXPECT_EQ(static_cast<double>(c.subgradients.cols()), c.cardinality);  // every piece of 𝕃 computed
  EXPECT_GT(c.cardinality, 1.0);
  // conv{ξ_i} contains the default piece's ξ: the full distance is never larger.
  EXPECT_LE(c.clarke.distance, c.default_piece.distance * (1 + 1e-12));
  EXPECT_NEAR(c.clarke.weights.sum(), 1.0, 1e-12);
  EXPECT_GE(c.clarke.weights.minCoeff(), 0.0);
  // Each R2 node contributes λ = 0, gap = 0, q = 0 and u_t = 0: two conditions beyond a piece's
  // two rows (the row-table reading in certificate.cpp).
  ASSERT_TRUE(c.mf1.computed);
  EXPECT_EQ(c.mf1.extra_conditions, 2 * p);
  EXPECT_EQ(c.mf1.rows, 2 * p + c.mf1.extra_conditions);
  EXPECT_EQ(c.mf1.cols, 15 + 2 * p);
  // Zero load: z = 0 gives u = 0 whatever α, so u_t cannot be steered by the design and the
  // u_t = 0 rows are dependent (one per node); the row table (λ, q, gap per node) is full rank.
  EXPECT_EQ(c.mf1.rows - c.mf1.rank, p);
  EXPECT_EQ(c.mf1.spec_rows, 3 * p);
  EXPECT_TRUE(c.mf1.spec_full_row_rank);
  // The extreme-point test ran on the full 𝕃 and δ_M bounds δ from above.
  ASSERT_TRUE(c.mordukhovich.computed) << c.mordukhovich.message;
  EXPECT_FALSE(c.mordukhovich.extreme.empty());
  EXPECT_GE(c.mordukhovich.distance, c.clarke.distance * (1 - 1e-10));

  // A cap below |𝕃| samples and skips the Mordukhovich check.
  CertifyOptions small;
  small.cap = 3;
  const Certificate s = certify(oracle, alpha, small);
  ASSERT_EQ(s.status, Status::kConverged) << s.message;
  EXPECT_TRUE(s.sampled);
  EXPECT_EQ(s.cardinality, c.cardinality);
  EXPECT_EQ(s.subgradients.cols(), 3);
  EXPECT_FALSE(s.mordukhovich.computed);
}

TEST(Certify, DistanceFallsAlongAShortOptimization) {
  ElasticBody body(thesis_body_2d(20, 8));
  ShapeOracle oracle(body, cost::make_compliance());
  const Eigen::VectorXd alpha0 = body.definition().initial_design;
  const Certificate before = certify(oracle, alpha0);
  ASSERT_EQ(before.status, Status::kConverged) << before.message;
  optim::BundleTrust::Options options = default_study_options(body.definition());
  options.max_iterations = 15;
  const optim::BundleTrust::Summary run = optimize(oracle, options, {});
  const Certificate after = certify(oracle, run.x);
  ASSERT_EQ(after.status, Status::kConverged) << after.message;
  std::printf("before: %s\nafter %d iterations: %s", before.report().c_str(), run.iterations, after.report().c_str());
  EXPECT_LT(after.value, before.value);
  EXPECT_LT(after.clarke.distance, before.clarke.distance);
}

// A study run that says "converged" must pass `certify`'s test (the exact Clarke
// distance at x over all enumerated pieces, relative tolerance 1e-3), not only the optimizer's
// bundle certificate. With ε = 0.1 the optimizer's own test and certificate pass early, at a
// point whose Clarke distance is above 1e-3 of max‖ξ‖: the run must say so (stalled, not
// certified), and whatever it says must agree with certify.
TEST(Certify, StudyRunSaysConvergedOnlyWhenCertifyAgrees) {
  ElasticBody body(thesis_body_2d(20, 8));
  ShapeOracle oracle(body, cost::make_compliance());
  optim::BundleTrust::Options options = default_study_options(body.definition());
  options.epsilon = 0.1;
  const optim::BundleTrust::Summary run = optimize(oracle, options, {});
  const Certificate c = certify(oracle, run.x);
  ASSERT_EQ(c.status, Status::kConverged) << c.message;
  std::printf("%s\ncertify: relative distance %.3e\n", run.brief_report().c_str(), c.relative_distance);
  EXPECT_EQ(run.converged(), c.clarke_stationary) << run.brief_report();
  EXPECT_EQ(run.stop_reason, optim::StopReason::kStationarityNotCertified) << run.brief_report();
  EXPECT_NE(run.message.find("frictopt certify"), std::string::npos) << run.message;
  // The check computes the Clarke distance alone.
  CertifyOptions clarke_only;
  clarke_only.clarke_only = true;
  const Certificate q = certify(oracle, run.x, clarke_only);
  ASSERT_EQ(q.status, Status::kConverged) << q.message;
  EXPECT_DOUBLE_EQ(q.clarke.distance, c.clarke.distance);
  EXPECT_FALSE(q.mf1.computed);
  EXPECT_FALSE(q.mf1.not_computed_reason.empty());
  EXPECT_FALSE(q.mordukhovich.computed);
}

TEST(Certify, RejectsBadInput) {
  ElasticBody body(thesis_body_2d(6, 2));
  ShapeOracle oracle(body, cost::make_compliance());
  EXPECT_THROW((void)certify(oracle, Eigen::VectorXd::Constant(14, 0.05)), InvalidInput);
  CertifyOptions bad;
  bad.cap = 0;
  EXPECT_THROW((void)certify(oracle, body.definition().initial_design, bad), InvalidInput);
  // Outside Υ (volume equality violated): N_Υ is undefined there; refused before any state solve.
  const int solves = oracle.num_state_solves();
  try {
    (void)certify(oracle, Eigen::VectorXd::Constant(15, 0.1));
    ADD_FAILURE() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("violates the admissible set"), std::string::npos) << e.what();
  }
  EXPECT_EQ(oracle.num_state_solves(), solves);
}

}  // namespace
}  // namespace frictopt::study
