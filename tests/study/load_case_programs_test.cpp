// SPDX-License-Identifier: MIT
// Load cases given as loading programs (docs/theory/load-cases.md §5): each case
// a history of its own ([[load_case.step]]), combined by the worst case or a weighted sum. The
// weighted ξ against central differences where every step of every case is strict; the worst
// case at a strictly active case is that case's history oracle; a static case among programs is
// the plain static problem with its scaled loads; one factorization per design for all
// steps of all cases; certify varies each active case's steps; bad input names the field.
#include <gtest/gtest.h>

#include <cstdio>
#include <optional>
#include <string>

#include "common/case_text.hpp"
#include "common/finite_difference.hpp"
#include "common/oracle_gradient.hpp"
#include "common/invalid_case.hpp"
#include "common/test_bodies.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/study/certificate.hpp"
#include "frictopt/study/cost_factory.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::study {
namespace {

using frictopt::testing::two_load_body_2d;

LoadStepDefinition step(std::vector<double> load_scale) {
  LoadStepDefinition s;
  s.load_scale = std::move(load_scale);
  return s;
}

// Case "long": the three steps of history_test's 2D program (strict at α⁰ in every step); case
// "short": its first two steps, so its history is a prefix of the long one's.
LoadCaseDefinition program_case(std::string name, std::vector<LoadStepDefinition> steps, double weight = 1.0) {
  LoadCaseDefinition c;
  c.name = std::move(name);
  c.weight = weight;
  c.program = LoadingProgramDefinition{std::move(steps)};
  return c;
}
LoadCaseDefinition long_case(double weight = 1.0) {
  return program_case("long", {step({0.5, 0.0}), step({1.0, 1.0}), step({1.1, 0.8})}, weight);
}
LoadCaseDefinition short_case(double weight = 1.0) {
  return program_case("short", {step({0.5, 0.0}), step({1.0, 1.0})}, weight);
}
LoadCaseDefinition static_case(std::string name, std::vector<double> load_scale, double weight = 1.0) {
  LoadCaseDefinition c;
  c.name = std::move(name);
  c.load_scale = std::move(load_scale);
  c.weight = weight;
  return c;
}

CostDefinition cases_cost(cost::CostKind kind, CaseCombination combine, std::vector<LoadCaseDefinition> cases) {
  CostDefinition d;
  d.kind = kind;
  d.exponent = 2.0;
  d.load_cases = LoadCasesDefinition{combine, std::move(cases)};
  return d;
}

using frictopt::testing::oracle_central_gradient;

void expect_every_step_strict(ShapeOracle& oracle, const Eigen::VectorXd& alpha) {
  for (int k = 0; k < oracle.load_cases()->size(); ++k) {
    ProgramHistory& h = oracle.program(alpha, k);
    for (int s = 0; s < h.num_steps(); ++s)
      ASSERT_EQ(h.index_sets(s).num_weak_nodes(), 0)
          << "case " << k << ", step " << s + 1 << " must be strict: " << h.index_sets(s).summary();
  }
}

struct FdCase {
  std::string name;
  cost::CostKind kind;
  int step;  // 0 = last
};

class ProgramCasesGradient : public ::testing::TestWithParam<FdCase> {};

TEST_P(ProgramCasesGradient, WeightedMatchesCentralDifferencesWhereEveryStepIsStrict) {
  const FdCase& c = GetParam();
  ElasticBody body(two_load_body_2d());
  CostDefinition d = cases_cost(c.kind, CaseCombination::kWeighted, {long_case(0.7), short_case(1.3)});
  d.step = c.step;
  ShapeOracle oracle(body, d);
  const Eigen::VectorXd alpha = body.definition().initial_design;
  const Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  expect_every_step_strict(oracle, alpha);
  EXPECT_DOUBLE_EQ(e.value, 0.7 * e.case_values[0] + 1.3 * e.case_values[1]);
  const Eigen::VectorXd fd = oracle_central_gradient(oracle, alpha);
  const double error = (e.subgradient - fd).norm() / fd.norm();
  std::printf("%s: J = (%.8e, %.8e), |ξ − FD|/|FD| = %.2e\n", c.name.c_str(), e.case_values[0], e.case_values[1],
              error);
  EXPECT_LE(error, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Costs, ProgramCasesGradient,
                         ::testing::Values(FdCase{"Dissipation", cost::CostKind::kDissipation, 0},
                                           FdCase{"ForcePowerLastStep", cost::CostKind::kNormalForcePower, 0},
                                           FdCase{"PressureNormStep2", cost::CostKind::kPressureNorm, 2}),
                         [](const ::testing::TestParamInfo<FdCase>& p) { return p.param.name; });

TEST(ProgramCases, WorstCaseAtAStrictlyActiveCaseIsThatCasesHistory) {
  ElasticBody body(two_load_body_2d()), single_body(two_load_body_2d());
  // The short program dissipates almost as much (its last step adds little): weight 0.9 makes the
  // long one strictly active.
  ShapeOracle oracle(body,
                     cases_cost(cost::CostKind::kDissipation, CaseCombination::kWorst, {short_case(0.9), long_case()}));
  const Eigen::VectorXd alpha = body.definition().initial_design;
  const Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  std::printf("worst: D = (%.8e, %.8e), selected %d\n", e.case_values[0], e.case_values[1], e.selected_case);
  ASSERT_EQ(e.selected_case, 1);
  ASSERT_LT(0.9 * e.case_values[0], 0.99 * e.value) << "strictly active";
  EXPECT_EQ(e.step_index_sets.size(), 3u) << "the selected case's steps";
  // The long program alone as a [[program.step]] history: the same value and ξ.
  CostDefinition single;
  single.kind = cost::CostKind::kDissipation;
  single.program = std::make_shared<const LoadingProgramDefinition>(*long_case().program);
  ShapeOracle history(single_body, single);
  const Evaluation h = history.evaluate_design(alpha);
  ASSERT_TRUE(h.ok) << h.message;
  EXPECT_EQ(h.value, e.value);
  EXPECT_LE((h.subgradient - e.subgradient).norm(), 1e-12 * e.subgradient.norm());
  const Eigen::VectorXd fd = oracle_central_gradient(oracle, alpha);
  const double error = (e.subgradient - fd).norm() / fd.norm();
  std::printf("worst, strictly active: |ξ − FD|/|FD| = %.2e\n", error);
  EXPECT_LE(error, 1e-6);
}

TEST(ProgramCases, AStaticCaseAmongProgramsIsTheStaticProblemWithItsLoads) {
  // An independent reference: the plain static oracle (no load cases, no program) on a body whose
  // two tractions are scaled by the case's (0.8, 2.0). The case's step adds (s − 1)·l_j to the
  // case file's load instead, and its ξ gains the load-change term: same J and ξ up to rounding.
  ElasticBody body(two_load_body_2d());
  BodyDefinition scaled = two_load_body_2d();
  scaled.tractions[0].traction *= 0.8;
  scaled.tractions[1].traction *= 2.0;
  ElasticBody static_body(scaled);
  ShapeOracle mixed(body, cases_cost(cost::CostKind::kNormalForcePower, CaseCombination::kWeighted,
                                     {static_case("pull", {0.8, 2.0}), short_case(0.0)}));
  CostDefinition plain;
  plain.kind = cost::CostKind::kNormalForcePower;
  plain.exponent = 2.0;
  ShapeOracle alone(static_body, plain);
  const Eigen::VectorXd alpha = body.definition().initial_design;
  const Evaluation m = mixed.evaluate_design(alpha);
  const Evaluation a = alone.evaluate_design(alpha);
  ASSERT_TRUE(m.ok && a.ok) << m.message << a.message;
  std::printf("static case vs static problem: J %.12e vs %.12e, |Δξ|/|ξ| = %.2e\n", m.case_values[0], a.value,
              (m.subgradient - a.subgradient).norm() / a.subgradient.norm());
  // Measured 7.4e-15 for both: round-off of two summation orders of the same load.
  EXPECT_NEAR(m.case_values[0], a.value, 1e-12 * a.value);
  EXPECT_EQ(m.value, m.case_values[0]) << "the zero-weight program case drops out";
  EXPECT_LE((m.subgradient - a.subgradient).norm(), 1e-12 * a.subgradient.norm());
}

TEST(ProgramCases, OneFactorizationForEveryStepOfEveryCase) {
  ElasticBody body(two_load_body_2d());
  ShapeOracle oracle(body, cases_cost(cost::CostKind::kDissipation, CaseCombination::kWeighted,
                                      {long_case(), short_case(), static_case("pull", {0.8, 2.0})}));
  const Eigen::VectorXd alpha = body.definition().initial_design;
  const Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_EQ(e.factorizations, 1) << "6 contact solves on one factorization";
  // The shape-derivative kernels of the scaled [[load]] tables are the body's: one per load,
  // shared by the three cases' six steps (each holds the mesh's element pattern).
  EXPECT_EQ(body.num_traction_kernels(), 2);
  Eigen::VectorXd moved = alpha;
  moved(1) += 1e-5;
  moved(2) -= 1e-5;  // the volume stays
  const Evaluation f = oracle.evaluate_design(moved);
  ASSERT_TRUE(f.ok) << f.message;
  EXPECT_EQ(f.factorizations, 1);
}

TEST(ProgramCases, CertifyVariesEachActiveCasesStepsAndSkipsMf1) {
  ElasticBody body(two_load_body_2d());
  ShapeOracle oracle(body, cases_cost(cost::CostKind::kDissipation, CaseCombination::kWeighted,
                                      {long_case(0.7), short_case(1.3)}));
  const Eigen::VectorXd alpha = body.definition().initial_design;
  const Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  const Certificate c = certify(oracle, alpha);
  ASSERT_EQ(c.status, Status::kConverged) << c.message;
  std::printf("%s", c.report().c_str());
  // Strict everywhere: one generator per case, their weighted sum is the oracle's ξ.
  ASSERT_EQ(c.subgradients.cols(), 1);
  EXPECT_LE((c.subgradients.col(0) - e.subgradient).norm(), 1e-12 * e.subgradient.norm());
  EXPECT_EQ(c.cardinality, 1.0);
  ASSERT_EQ(c.history_steps.size(), 5u) << "3 + 2 steps";
  EXPECT_EQ(c.history_steps.front().rfind("long, step 1", 0), 0u) << c.history_steps.front();
  for (const LoadCaseCertificate& lc : c.load_cases) {
    EXPECT_TRUE(lc.active);
    EXPECT_FALSE(lc.mf1.computed);
    EXPECT_NE(lc.mf1.not_computed_reason.find("loading program"), std::string::npos);
  }
}

// ---------------------------------------------------------------------------------------------
// Bad input: the oracle's checks and the case file's, each naming the field.

std::string expect_refused(const CostDefinition& d) {
  ElasticBody body(two_load_body_2d());
  try {
    ShapeOracle oracle(body, d);
  } catch (const InvalidInput& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted";
  return {};
}

TEST(ProgramCasesInput, TheOracleRefusesWhatHasNoMeaning) {
  LoadCaseDefinition both = long_case();
  both.load_scale = {1.0, 1.0};
  EXPECT_NE(expect_refused(cases_cost(cost::CostKind::kDissipation, CaseCombination::kWorst, {both}))
                .find("load_case[0] (\"long\") has both scale lists and [[load_case.step]] tables"),
            std::string::npos);
  CostDefinition beyond = cases_cost(cost::CostKind::kNormalForcePower, CaseCombination::kWorst, {long_case(), short_case()});
  beyond.step = 3;
  EXPECT_NE(expect_refused(beyond).find("cost: expected \"last\" or an integer step in [1, 2] (load case 2 \"short\" has 2 steps"),
            std::string::npos);
  EXPECT_NE(expect_refused(cases_cost(cost::CostKind::kDissipation, CaseCombination::kWorst, {static_case("a", {1.0, 1.0})}))
                .find("cost: expected a cost of one state (the loads are one step"),
            std::string::npos);
  CostDefinition with_program = cases_cost(cost::CostKind::kDissipation, CaseCombination::kWorst, {long_case()});
  with_program.program = std::make_shared<const LoadingProgramDefinition>(*short_case().program);
  EXPECT_NE(expect_refused(with_program).find("cost: expected a loading program or load cases, not both"), std::string::npos);
  LoadCaseDefinition wrong = short_case();
  wrong.program->steps[1].load_scale = {1.0};
  EXPECT_NE(expect_refused(cases_cost(cost::CostKind::kDissipation, CaseCombination::kWorst, {wrong}))
                .find("load_case[0].step[1].load_scale has 1 entries, but the case has 2 [[load]] tables"),
            std::string::npos);
}

// The pushed 3D block (common/case_text.hpp), a [cost] and `extra`.
std::string block_case(const std::string& cost, const std::string& extra) {
  return frictopt::testing::pushed_block_3d() + cost + extra;
}

const std::string kTwoPrograms = R"(
[[load_case]]
name = "press"
[[load_case.step]]
dirichlet_scale = [0.5]
[[load_case.step]]
label = "full"
dirichlet_scale = [1.0]
load_scale = [2.0]
[[load_case]]
name = "static"
load_scale = [0.0]
)";

TEST(ProgramCasesInput, ProgramsParse) {
  const io::CaseDescription c = io::parse_case(block_case("[cost]\nkind = \"pressure_norm\"\nstep = 1\n", kTwoPrograms),
                                               "ok.toml");
  ASSERT_TRUE(c.cost && c.cost->load_cases);
  const LoadCasesDefinition& d = *c.cost->load_cases;
  ASSERT_EQ(d.cases.size(), 2u);
  ASSERT_TRUE(d.cases[0].program.has_value());
  ASSERT_EQ(d.cases[0].program->steps.size(), 2u);
  EXPECT_EQ(d.cases[0].program->steps[1].label, "full");
  EXPECT_EQ(d.cases[0].program->steps[1].load_scale, std::vector<double>{2.0});
  EXPECT_FALSE(d.cases[1].program.has_value());
  EXPECT_EQ(c.cost->step, 1);
  EXPECT_EQ(c.cost->program, nullptr) << "the programs belong to the cases";
  EXPECT_EQ(c.problem_settings.count("load_case[0].step[1].load_scale"), 1u) << "the run's fingerprint sees the steps";
  // The dissipation is a history cost of the program cases (the static case dissipates over its one step).
  EXPECT_NO_THROW((void)io::parse_case(block_case("[cost]\nkind = \"dissipation\"\n", kTwoPrograms), "ok.toml"));
}

// The combination rules of a cost with its loads, in the model's terms (study/cost_factory.hpp):
// the part each rule names, which the case reader turns into cost.kind or cost.step.
TEST(CostCombination, EachRuleNamesItsPart) {
  using Part = CostCombinationProblem::Part;
  const auto part_of = [](const CostDefinition& d) {
    const auto problem = find_combination_problem(d);
    return problem ? std::optional<Part>(problem->part) : std::nullopt;
  };
  CostDefinition one_state = cases_cost(cost::CostKind::kNormalForcePower, CaseCombination::kWorst, {});
  one_state.load_cases.reset();
  EXPECT_EQ(part_of(one_state), std::nullopt) << "a cost of the static problem";
  CostDefinition compliance = one_state;
  compliance.kind = cost::CostKind::kCompliance;
  EXPECT_EQ(part_of(compliance), std::nullopt) << "the compliance of the case's own loads";
  CostDefinition stepped = one_state;
  stepped.step = 1;
  EXPECT_EQ(part_of(stepped), Part::kStep) << "a step of a one-step problem";
  CostDefinition dissipation = one_state;
  dissipation.kind = cost::CostKind::kDissipation;
  EXPECT_EQ(part_of(dissipation), Part::kKind) << "the dissipation of one state";

  CostDefinition programs = cases_cost(cost::CostKind::kNormalForcePower, CaseCombination::kWorst,
                                       {long_case(), short_case()});
  EXPECT_EQ(part_of(programs), std::nullopt);
  programs.step = 2;
  EXPECT_EQ(part_of(programs), std::nullopt) << "step 2 exists in both programs";
  programs.step = 3;
  ASSERT_EQ(part_of(programs), Part::kStep);
  EXPECT_NE(find_combination_problem(programs)->expectation.find("[1, 2] (load case 2 \"short\" has 2 steps)"),
            std::string::npos);
  programs.step = -1;
  EXPECT_EQ(part_of(programs), Part::kStep);
  programs.step = 0;
  programs.kind = cost::CostKind::kCompliance;
  EXPECT_EQ(part_of(programs), Part::kKind) << "the compliance of a case's loads";
  programs.kind = cost::CostKind::kDissipation;
  EXPECT_EQ(part_of(programs), std::nullopt);
  programs.step = 1;
  EXPECT_EQ(part_of(programs), Part::kStep) << "the dissipation reads every step";
  programs.step = 0;
  programs.program = std::make_shared<const LoadingProgramDefinition>(*short_case().program);
  EXPECT_EQ(part_of(programs), Part::kLoads) << "a program and load cases";
  EXPECT_THROW(validate_combination(programs), InvalidInput);
}

TEST(ProgramCasesInput, BadInputNamesTheField) {
  using frictopt::testing::expect_invalid_case;
  const std::string press = "[[load_case]]\nname = \"press\"\n";
  const std::string cost = "[cost]\nkind = \"pressure_norm\"\n";
  expect_invalid_case(block_case(cost, press + "load_scale = [1.0]\n[[load_case.step]]\ndirichlet_scale = [1.0]\n"),
                      {"load_case[0].load_scale with [[load_case.step]] tables", "either"});
  expect_invalid_case(block_case(cost, press + "[[load_case.step]]\ndirichlet_scale = [1.0, 2.0]\n"),
                      {"load_case[0].step[0].dirichlet_scale has 2 entries, but the case has 1 [[dirichlet]] table"});
  expect_invalid_case(block_case(cost, press + "[[load_case.step]]\ndirichlet_scale = [1.0]\nfrction = false\n"),
                      {"load_case[0].step[0]", "frction"});
  // A step beyond the fewest steps of any case (the static case has one).
  expect_invalid_case(block_case(cost + "step = 2\n", kTwoPrograms),
                      {"cost.step = 2", "[1, 1]", "load case 2 \"static\" is a static load: one step"});
  expect_invalid_case(block_case(cost + "step = 3\n", press + "[[load_case.step]]\n[[load_case.step]]\n"),
                      {"cost.step = 3", "[1, 2]", "load case 1 \"press\" has 2 steps"});
  // No case has steps: a history cost on one-step cases.
  expect_invalid_case(block_case("[cost]\nkind = \"dissipation\"\n", press), {"cost.kind = \"dissipation\"", "one state"});
  expect_invalid_case(block_case(cost + "step = 1\n", press), {"cost.step = 1", "no step"});
  // The compliance reads the case file's own loads, not a case's (refused with its line since the
  // reader checks the model's combination rules; before, only the shape oracle refused it).
  expect_invalid_case(block_case("[cost]\nkind = \"compliance\"\n", press + "load_scale = [1.0]\n"),
                      {"cost.kind = \"compliance\"", "a contact cost", "not a step's or a case's"});
  // [[program.step]] and [[load_case]] together.
  expect_invalid_case(block_case(cost, press + "[[program.step]]\ndirichlet_scale = [1.0]\n"),
                      {"[[program.step]] tables with [[load_case]] tables", "[[load_case.step]]"});
}

}  // namespace
}  // namespace frictopt::study
