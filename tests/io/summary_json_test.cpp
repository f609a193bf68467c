// SPDX-License-Identifier: MIT
// io::to_json of the solver Summaries: every field under its own name, enums in their report
// spelling, NaN (not computed) as null, and the JSON text reads back.
#include "frictopt/io/summary_json.hpp"

#include <gtest/gtest.h>

namespace frictopt::io {
namespace {

TEST(SummaryJson, ANotRunSummaryKeepsItsNaNsAsNull) {
  const contact::CoulombSolver::Summary coulomb;
  const JsonValue j = parse_json(to_json_string(to_json(coulomb)));
  EXPECT_EQ(j.at("status").as_string(), "not_run");
  EXPECT_TRUE(j.at("kkt_residual").is_null());
  EXPECT_EQ(j.at("method_used").as_string(), std::string(contact::to_string(coulomb.method_used)));
  EXPECT_TRUE(parse_json(to_json_string(to_json(contact::TrescaSolver::Summary{}))).at("objective").is_null());
  EXPECT_TRUE(parse_json(to_json_string(to_json(sensitivity::AdjointSensitivity::Summary{}))).at(
      "reciprocal_condition").is_null());
  EXPECT_TRUE(parse_json(to_json_string(to_json(study::StateSummary{}))).at("relative_residual").is_null());
  EXPECT_EQ(to_json(optim::DenseQpSolver::Summary{}).at("outcome").as_string(),
            std::string(optim::to_string(optim::QpOutcome::kNotRun)));
  EXPECT_EQ(to_json(optim::ProjectedSubgradient::Summary{}).at("evaluations").as_integer(), 0);
  EXPECT_EQ(to_json(study::Identification::Summary{}).at("estimates").as_array().size(), 0u);
}

TEST(SummaryJson, TheBundleTrustSummaryNamesTheLimitThatStoppedIt) {
  optim::BundleTrust::Summary s;
  s.status = Status::kMaxIterations;
  s.evaluation_limit = true;
  s.x = Eigen::VectorXd::Constant(2, 0.5);
  s.iterations = 7;
  const JsonValue j = to_json(s);
  EXPECT_EQ(j.at("status").as_string(), "max_iterations");
  EXPECT_EQ(j.at("stopped_by").as_string(), "max_evaluations");
  EXPECT_EQ(j.at("iterations").as_integer(), 7);
  EXPECT_EQ(j.at("x").as_array().size(), 2u);
  JsonValue into = JsonValue::object();
  into["command"] = "optimize";
  add_members(into, j);
  EXPECT_EQ(into.at("command").as_string(), "optimize");
  EXPECT_EQ(into.at("stopped_by").as_string(), "max_evaluations");
}

TEST(SummaryJson, TheCostUnitFollowsTheCostAndTheDimension) {
  study::CostDefinition cost;
  cost.kind = cost::CostKind::kTargetPressure;  // Σ(λ̄ − λ)², λ in N (2D: N/m)
  EXPECT_EQ(cost_unit(cost, 3), "N²");
  EXPECT_EQ(cost_unit(cost, 2), "N²/m²");
  cost.kind = cost::CostKind::kNormalForcePower;
  cost.exponent = 4.0;
  EXPECT_EQ(cost_unit(cost, 3), "N⁴");
  EXPECT_EQ(cost_unit(cost, 2), "(N/m)⁴");
  cost.exponent = 2.5;
  EXPECT_EQ(cost_unit(cost, 3), "N^2.5");
  cost.kind = cost::CostKind::kCompliance;
  EXPECT_EQ(cost_unit(cost, 3), "J");
  EXPECT_EQ(cost_unit(cost, 2), "J/m");
  cost.kind = cost::CostKind::kPressureNorm;
  cost.exponent = 8.0;
  EXPECT_EQ(cost_unit(cost, 3), "Pa·m^0.25");
  cost.kind = cost::CostKind::kTotalSlip;
  EXPECT_EQ(cost_unit(cost, 2), "m");
  cost.kind = cost::CostKind::kTractionUniformity;
  EXPECT_EQ(cost_unit(cost, 3), "Pa²·m²");
  cost.kind = cost::CostKind::kDissipation;
  EXPECT_EQ(cost_unit(cost, 3), "J");
}

}  // namespace
}  // namespace frictopt::io
