// SPDX-License-Identifier: MIT
// study::check_gradient (what `frictopt check-gradient` prints) at the flat start α⁰ = 0, the
// first check a user runs: the step is relative to the width of the design's bounds (C0), not to
// max|α| (which made h = 1e-16 m there, and the check void); a step below the state's accuracy
// is flagged; the nodes that change piece within ±h are reported with both one-sided quotients.
// And study::assess_outcome, the verdict behind optimize's exit codes.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "frictopt/io/case_file.hpp"
#include "frictopt/study/derivative_accuracy.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/gradient_check.hpp"
#include "frictopt/study/shape_optimization.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::study {
namespace {

// A flat block (α⁰ = 0: the whole bottom on the foundation) pressed 20 µm and dragged 5 µm, a
// 3 × 3 net bounded by C0 = 1 mm, compliance cost, isotropic 16-gon friction.
constexpr double kUpperBound = 1.0e-3;
const char* const kFlatCase = R"(
[geometry]
dim = 3
a = 1.0
b = 1.0
height = 0.5
[mesh]
cells = [6, 6, 3]
[material]
young = 7.0e10
poisson = 0.33
[[dirichlet]]
face = "top"
displacement = [5.0e-6, 0.0, -2.0e-5]
[design]
control_points = [3, 3]
initial = 0.0
upper_bound = 1.0e-3
[contact.friction]
kind = "isotropic"
mu = 0.3
[cost]
kind = "compliance"
)";

struct FlatBlock {
  io::CaseDescription description = io::parse_case(kFlatCase, "flat.toml");
  std::unique_ptr<ElasticBody> body;
  std::unique_ptr<ShapeOracle> oracle;
  FlatBlock() {
    BodyDefinition definition = description.body;
    tighten_for_derivatives(definition.contact->coulomb);
    body = std::make_unique<ElasticBody>(definition);
    oracle = std::make_unique<ShapeOracle>(*body, description.required_cost());
  }
};

TEST(GradientCheck, AtTheFlatStartTheStepIsRelativeToTheBoundsNotToMaxAlpha) {
  FlatBlock s;
  const Eigen::VectorXd alpha = s.body->initial_design();
  ASSERT_EQ(alpha.cwiseAbs().maxCoeff(), 0.0);
  const GradientCheck check = check_gradient(*s.oracle, alpha, 1e-4);
  ASSERT_TRUE(check.evaluation.ok) << check.evaluation.message;
  // h = 1e-4 · C0 = 1e-7 m for every control height (was 1e-4 · max(max|α|, 1e-12) = 1e-16 m).
  EXPECT_DOUBLE_EQ(check.step, 1e-4 * kUpperBound);
  for (const auto& c : check.components) EXPECT_DOUBLE_EQ(c.step, 1e-4 * kUpperBound);
  EXPECT_TRUE(check.warnings.empty()) << check.warnings.front();
  EXPECT_LT(check.noise_relative, 1e-3);
  // Every component either matches ξ or sits at a kink that the report explains.
  for (std::size_t k = 0; k < check.components.size(); ++k) {
    const auto& c = check.components[k];
    EXPECT_NE(c.verdict, GradientCheck::Verdict::kMismatch)
        << "component " << k << ": central " << c.finite_difference << ", forward " << c.forward_difference
        << ", backward " << c.backward_difference << ", adjoint " << c.adjoint;
    if (c.piece_changes.empty()) {
      EXPECT_LT(c.relative_error, kGradientCheckAgreement) << "component " << k;
    }
  }
}

TEST(GradientCheck, AStepBelowTheStatesAccuracyIsFlagged) {
  // The old rule's step at α = 0 (1e-16 relative): the quotients are round-off, and the check says so.
  FlatBlock s;
  const GradientCheck check = check_gradient(*s.oracle, s.body->initial_design(), 1e-16);
  ASSERT_TRUE(check.evaluation.ok);
  EXPECT_GT(check.noise_relative, 1e-2);
  ASSERT_FALSE(check.warnings.empty());
  EXPECT_NE(check.warnings.front().find("too small for the state's accuracy"), std::string::npos)
      << check.warnings.front();
}

TEST(GradientCheck, NodesChangingPieceWithinTheStepAreReportedWithOneSidedQuotients) {
  // A step of 10 % of C0 = 100 µm lifts parts of the bottom (pressed 20 µm) off the foundation:
  // the nodes leaving contact are listed, and the one-sided quotients differ there.
  FlatBlock s;
  const GradientCheck check = check_gradient(*s.oracle, s.body->initial_design(), 0.1);
  ASSERT_TRUE(check.evaluation.ok);
  bool lifted = false;
  for (const auto& c : check.components) {
    EXPECT_TRUE(std::isfinite(c.forward_difference) && std::isfinite(c.backward_difference));
    EXPECT_NEAR(c.finite_difference, 0.5 * (c.forward_difference + c.backward_difference),
                1e-9 * std::abs(c.forward_difference) + 1e-300);
    for (const auto& p : c.piece_changes) {
      EXPECT_TRUE(p.side == 1 || p.side == -1);
      EXPECT_NE(p.before, p.after);
      EXPECT_GE(p.node, 0);
      EXPECT_LT(p.node, s.body->contact_boundary()->num_nodes());
      if (p.side == 1 && p.before.rfind("I+", 0) == 0 && p.after == "M") lifted = true;
    }
    if (c.verdict == GradientCheck::Verdict::kKink) {
      EXPECT_FALSE(c.piece_changes.empty());
    }
  }
  EXPECT_TRUE(lifted) << "no node reported leaving contact at +h";
}

// --- study::assess_outcome ------------------------------------------------------------------

sensitivity::IndexSets sets(int strong, int separated) {
  sensitivity::IndexSets s;
  sensitivity::NodeSets in;
  in.normal = sensitivity::NormalSet::kStrongContact;
  in.tangential = sensitivity::TangentialSet::kStrongStick;
  s.nodes.assign(static_cast<std::size_t>(strong), in);
  s.nodes.resize(static_cast<std::size_t>(strong + separated));  // the rest: M
  return s;
}

TEST(OptimizationOutcome, StatusesAndContactDecideIt) {
  using Kind = OptimizationOutcome::Kind;
  optim::BundleTrust::Summary summary;
  Evaluation final;
  final.ok = true;
  final.index_sets = sets(5, 3);
  summary.status = Status::kConverged;
  EXPECT_EQ(assess_outcome(summary, final).kind, Kind::kCertified);
  EXPECT_TRUE(assess_outcome(summary, final).attention.empty());
  summary.status = Status::kMaxIterations;
  EXPECT_EQ(assess_outcome(summary, final).kind, Kind::kLimitReached);
  summary.status = Status::kStalled;
  summary.stop_reason = optim::StopReason::kStationarityNotCertified;
  summary.message = "the certificate exceeded its bound";
  const OptimizationOutcome stalled = assess_outcome(summary, final);
  EXPECT_EQ(stalled.kind, Kind::kNeedsAttention);
  ASSERT_EQ(stalled.attention.size(), 1U);
  EXPECT_NE(stalled.attention[0].find("stationarity_not_certified"), std::string::npos) << stalled.attention[0];
  summary.status = Status::kNumericalFailure;
  EXPECT_EQ(assess_outcome(summary, final).kind, Kind::kFailed);
  summary.status = Status::kConverged;
  final.ok = false;
  EXPECT_EQ(assess_outcome(summary, final).kind, Kind::kFailed);
}

TEST(OptimizationOutcome, ACertifiedDesignWithoutContactNeedsAttention) {
  optim::BundleTrust::Summary summary;
  summary.status = Status::kConverged;
  Evaluation final;
  final.ok = true;
  final.index_sets = sets(0, 8);  // every node in M: the body has lifted off
  const OptimizationOutcome o = assess_outcome(summary, final);
  EXPECT_EQ(o.kind, OptimizationOutcome::Kind::kNeedsAttention);
  ASSERT_EQ(o.attention.size(), 1U);
  EXPECT_NE(o.attention[0].find("no contact at the final design"), std::string::npos) << o.attention[0];
  EXPECT_EQ(to_string(o.kind), "needs_attention");
}

}  // namespace
}  // namespace frictopt::study
