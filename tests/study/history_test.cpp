// SPDX-License-Identifier: MIT
// Costs along a loading history (docs/theory/history-adjoint.md): the backward
// adjoint's ξ against central differences where every step's index sets are strict (a last-step
// cost and the dissipation, 3D and 2D); without the steps' coupling ξ is wrong; at a kink each
// one-sided derivative is that of an enumerated selection of pieces; a one-step program is the
// static oracle; certify's generators; bad input names the field.
#include "frictopt/study/history.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include "common/finite_difference.hpp"
#include "common/oracle_gradient.hpp"
#include "common/test_bodies.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/study/certificate.hpp"
#include "frictopt/study/orientation_design.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::study {
namespace {

// The 3D block of the adjoint tests (dish-shaped bottom, rigid plate on top) with the plate's
// motion split into a press (component z) and a drag (x, y): programs scale the two.
BodyDefinition pressed_block_3d(const contact::FrictionLaw& law) {
  BodyDefinition b = frictopt::testing::dish_block_3d(law);
  b.dirichlet = {{"top", {2}, Eigen::Vector3d(0.0, 0.0, -1.2e-3)}, {"top", {0, 1}, Eigen::Vector3d(2e-4, 1e-4, 0.0)}};
  return b;
}

using frictopt::testing::two_load_body_2d;

LoadStepDefinition step(std::vector<double> load_scale, std::vector<double> dirichlet_scale, bool friction = true) {
  LoadStepDefinition s;
  s.load_scale = std::move(load_scale);
  s.dirichlet_scale = std::move(dirichlet_scale);
  s.friction = friction;
  return s;
}

// Press with friction (half the plate's travel, and a part of the drag), then the full press and
// drag: friction acts in both steps, so step 2's slip reference u_t^1 depends on the design.
std::shared_ptr<const LoadingProgramDefinition> press_then_drag_3d() {
  auto p = std::make_shared<LoadingProgramDefinition>();
  p->steps = {step({}, {0.95, 0.6}), step({}, {1.0, 0.8})};
  return p;
}

std::shared_ptr<const LoadingProgramDefinition> three_steps_2d() {
  auto p = std::make_shared<LoadingProgramDefinition>();
  p->steps = {step({0.5, 0.0}, {}), step({1.0, 1.0}, {}), step({1.1, 0.8}, {})};
  return p;
}

CostDefinition history_cost(cost::CostKind kind, std::shared_ptr<const LoadingProgramDefinition> program, int at = 0) {
  CostDefinition d;
  d.kind = kind;
  d.exponent = 2.0;
  d.program = std::move(program);
  d.step = at;
  return d;
}

using frictopt::testing::oracle_central_gradient;

void expect_strict(ShapeOracle& oracle, const Eigen::VectorXd& alpha) {
  ProgramHistory& h = *oracle.history();
  oracle.evaluate_design(alpha, false);
  for (int k = 0; k < h.num_steps(); ++k) {
    const Eigen::VectorXd& z = h.state(k)->contact->state.z;
    std::printf("  step %d: %s; |z| = %.3e\n", k + 1, h.index_sets(k).summary().c_str(), z.norm());
  }
  for (int k = 0; k < h.num_steps(); ++k)
    ASSERT_EQ(h.index_sets(k).num_weak_nodes(), 0) << "step " << k + 1 << " must be strict: " << h.index_sets(k).summary();
}

struct FdCase {
  std::string name;
  bool three_d;
  cost::CostKind kind;
  int step;  // 0 = last
};

class HistoryGradient : public ::testing::TestWithParam<FdCase> {};

TEST_P(HistoryGradient, MatchesCentralDifferencesWhereEveryStepIsStrict) {
  const FdCase& c = GetParam();
  ElasticBody body(c.three_d ? pressed_block_3d(contact::FrictionLaw::regular_polygon(0.3, 8)) : two_load_body_2d());
  ShapeOracle oracle(body, history_cost(c.kind, c.three_d ? press_then_drag_3d() : three_steps_2d(), c.step));
  const Eigen::VectorXd alpha = body.definition().initial_design;
  expect_strict(oracle, alpha);
  const Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  const Eigen::VectorXd fd = oracle_central_gradient(oracle, alpha);
  const double error = (e.subgradient - fd).norm() / fd.norm();
  std::printf("%s: Θ = %.10e, |ξ| = %.4e, relative error vs central differences %.2e\n", c.name.c_str(), e.value,
              e.subgradient.norm(), error);
  EXPECT_GT(std::abs(e.value), 0.0);
  EXPECT_LE(error, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(
    Costs, HistoryGradient,
    ::testing::Values(FdCase{"Block3D_ForcePower_LastStep", true, cost::CostKind::kNormalForcePower, 0},
                      FdCase{"Block3D_TractionUniformity_Step1", true, cost::CostKind::kTractionUniformity, 1},
                      FdCase{"Block3D_Dissipation", true, cost::CostKind::kDissipation, 0},
                      FdCase{"Thesis2D_ForcePower_LastStep", false, cost::CostKind::kNormalForcePower, 0},
                      FdCase{"Thesis2D_Dissipation", false, cost::CostKind::kDissipation, 0},
                      FdCase{"Thesis2D_PressureNorm_Step2", false, cost::CostKind::kPressureNorm, 2},
                      FdCase{"Thesis2D_TotalSlip_Step2", false, cost::CostKind::kTotalSlip, 2},
                      FdCase{"Thesis2D_TargetPressureInitialMean_Step1", false, cost::CostKind::kTargetPressure, 1},
                      FdCase{"Thesis2D_TractionUniformity_Last", false, cost::CostKind::kTractionUniformity, 0}),
    [](const ::testing::TestParamInfo<FdCase>& p) { return p.param.name; });

TEST(HistoryAdjoint, InitialMeanTargetIsThatOfTheStepTheCostReads) {
  // target = "initial_mean" after step 1 of three: λ̄ = (Σλ¹/Σa)·a from step 1's state at α⁰.
  ElasticBody body(two_load_body_2d());
  CostDefinition d = history_cost(cost::CostKind::kTargetPressure, three_steps_2d(), 1);  // target NaN
  ShapeOracle oracle(body, d);
  const Evaluation e = oracle.evaluate_design(body.definition().initial_design, false);
  ASSERT_TRUE(e.ok) << e.message;
  const Eigen::VectorXd lambda = oracle.history()->state(0)->contact->state.normal_forces();
  const Eigen::VectorXd& areas = body.contact_boundary()->tributary_areas();
  const double expected = ((lambda.sum() / areas.sum()) * areas - lambda).squaredNorm();
  std::printf("initial_mean after step 1: Θ(α⁰) = %.10e, expected %.10e\n", e.value, expected);
  EXPECT_NEAR(e.value, expected, 1e-12 * expected);
  // Not the last step's mean: that target would give another value.
  const Eigen::VectorXd last = oracle.history()->state(2)->contact->state.normal_forces();
  EXPECT_GT(std::abs(((last.sum() / areas.sum()) * areas - lambda).squaredNorm() - expected), 1e-3 * expected);
}

TEST(HistoryAdjoint, DroppingTheCouplingBetweenStepsIsWrong) {
  for (cost::CostKind kind : {cost::CostKind::kNormalForcePower, cost::CostKind::kDissipation}) {
    ElasticBody body(pressed_block_3d(contact::FrictionLaw::regular_polygon(0.3, 8)));
    ShapeOracle oracle(body, history_cost(kind, press_then_drag_3d()));
    const Eigen::VectorXd alpha = body.definition().initial_design;
    expect_strict(oracle, alpha);
    const Evaluation e = oracle.evaluate_design(alpha);
    ASSERT_TRUE(e.ok) << e.message;
    ProgramHistory& h = *oracle.history();
    const HistorySubgradient uncoupled = h.subgradient(h.default_pieces(), false);
    ASSERT_EQ(uncoupled.summary.status, Status::kConverged);
    const Eigen::VectorXd fd = oracle_central_gradient(oracle, alpha);
    const double coupled_error = (e.subgradient - fd).norm() / fd.norm();
    const double uncoupled_error = (uncoupled.subgradient - fd).norm() / fd.norm();
    std::printf("%s: relative error with the coupling %.2e, without %.2e\n", std::string(cost::to_string(kind)).c_str(),
                coupled_error, uncoupled_error);
    EXPECT_LE(coupled_error, 1e-6);
    EXPECT_GT(uncoupled_error, 1e-3);
  }
}

TEST(HistoryAdjoint, OneStepProgramIsTheStaticOracle) {
  for (cost::CostKind kind : {cost::CostKind::kNormalForcePower, cost::CostKind::kTargetPressure}) {
    ElasticBody static_body(two_load_body_2d()), program_body(two_load_body_2d());
    CostDefinition plain;
    plain.kind = kind;
    plain.exponent = 2.0;  // target_pressure: NaN target = "initial_mean"
    ShapeOracle reference(static_body, plain);
    auto one = std::make_shared<LoadingProgramDefinition>();
    one->steps.emplace_back();
    CostDefinition with_program = plain;
    with_program.program = one;
    ShapeOracle oracle(program_body, with_program);
    const Eigen::VectorXd alpha = static_body.definition().initial_design;
    const Evaluation a = reference.evaluate_design(alpha), b = oracle.evaluate_design(alpha);
    ASSERT_TRUE(a.ok && b.ok) << a.message << b.message;
    const double value_error = std::abs(a.value - b.value) / std::abs(a.value);
    const double xi_error = (a.subgradient - b.subgradient).norm() / a.subgradient.norm();
    const double mu_error = (a.friction_gradient - b.friction_gradient).norm() / a.friction_gradient.norm();
    std::printf("one-step program, %s: value %.2e, ξ %.2e, ∂Θ/∂p %.2e relative\n",
                std::string(cost::to_string(kind)).c_str(), value_error, xi_error, mu_error);
    EXPECT_LE(value_error, 1e-12);
    EXPECT_LE(xi_error, 1e-12);
    EXPECT_LE(mu_error, 1e-12);
  }
}

// The one evaluation path keeps the static path inside: the oracle's static problem is
// ElasticBody::solve's state, the cost's partials there and the state engine's subgradient, bit
// for bit (a refactor of the oracle must change no static result), and it alone has a state
// derivative and no warm starts of its own (the body's own warm start chains the designs).
TEST(HistoryAdjoint, TheStaticProblemIsTheBodysSolveAndTheEnginesSubgradientBitForBit) {
  ElasticBody oracle_body(two_load_body_2d()), direct_body(two_load_body_2d());
  CostDefinition plain;
  plain.kind = cost::CostKind::kNormalForcePower;
  plain.exponent = 2.0;
  ShapeOracle oracle(oracle_body, plain);
  ASSERT_EQ(oracle.num_programs(), 1);
  EXPECT_EQ(oracle.history(), nullptr) << "no [[program.step]] tables";
  const Eigen::VectorXd alpha = oracle_body.definition().initial_design;
  const Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_TRUE(oracle.program(alpha).is_static_problem());
  EXPECT_TRUE(oracle.history_warm_starts().empty());
  EXPECT_TRUE(e.step_index_sets.empty());

  const BodyState state = direct_body.solve(alpha, "design");
  const auto cost = make_cost(plain, direct_body, nullptr);
  const contact::ContactBoundary& boundary = *direct_body.contact_boundary();
  const sensitivity::CostPartials j = cost->evaluate({direct_body.elasticity(), boundary, state.alpha, state.positions,
                                                      state.displacement, state.contact->state,
                                                      boundary.tributary_areas()});
  const sensitivity::IndexSets sets = sensitivity::classify(state.contact->state, *state.contact->law);
  const auto xi = direct_body.engine().evaluation_subgradient(state, sensitivity::default_piece(sets), j,
                                                             boundary.gap_jacobian(direct_body.mesh()));
  EXPECT_EQ(e.value, j.value);
  EXPECT_EQ(e.index_sets.summary(), sets.summary());
  ASSERT_EQ(e.subgradient.size(), xi.subgradient.size());
  EXPECT_TRUE(e.subgradient == xi.subgradient) << "max |Δξ| = " << (e.subgradient - xi.subgradient).cwiseAbs().maxCoeff();
  EXPECT_TRUE(e.friction_gradient == xi.friction_gradient);
  const Eigen::VectorXd h = Eigen::VectorXd::Ones(alpha.size());
  EXPECT_EQ(oracle.state_derivative(alpha, h).contact.size(), state.contact->state.z.size());
}

TEST(HistoryAdjoint, FrictionGradientMatchesCentralDifferences) {
  // Σ_k of each friction step's ∂/∂μ rows (docs/theory/history-adjoint.md §4), here for the disc's
  // one coefficient approximated by the regular polygon's circumradius.
  const auto theta = [](const Eigen::VectorXd& mu) {
    ElasticBody b(pressed_block_3d(contact::FrictionLaw::regular_polygon(mu(0), 8)));
    ShapeOracle o(b, history_cost(cost::CostKind::kDissipation, press_then_drag_3d()));
    return o.evaluate_design(b.definition().initial_design, false).value;
  };
  ElasticBody body(pressed_block_3d(contact::FrictionLaw::regular_polygon(0.3, 8)));
  ShapeOracle oracle(body, history_cost(cost::CostKind::kDissipation, press_then_drag_3d()));
  const Evaluation e = oracle.evaluate_design(body.definition().initial_design);
  ASSERT_TRUE(e.ok) << e.message;
  ASSERT_EQ(e.friction_gradient.size(), 1);
  const Eigen::VectorXd fd = frictopt::testing::central_gradient(theta, Eigen::VectorXd::Constant(1, 0.3), 1e-5);
  std::printf("dissipation: dΘ/dμ adjoint %.10e, FD %.10e\n", e.friction_gradient(0), fd(0));
  EXPECT_LE(std::abs(e.friction_gradient(0) - fd(0)), 1e-5 * std::abs(fd(0)));
}

TEST(HistoryAdjoint, FrictionOrientationAsADesignVariableMatchesCentralDifferences) {
  // x = (α, s) with [design] friction_orientation (docs/theory/friction-design.md): the law turns
  // in every friction step, so ∂Θ/∂s = Σ_k (∂r_k/∂s)ᵀ ψ_z^k over the backward adjoint's steps.
  // The 8-gon turned by 0.1 rad (anisotropic enough to depend on φ, strict in both steps).
  BodyDefinition definition = pressed_block_3d(contact::FrictionLaw::regular_polygon(0.3, 8).rotated(0.1));
  definition.friction_orientation = OrientationDesignDefinition{-1.5, 1.5};
  ElasticBody body(definition);
  ShapeOracle oracle(body, history_cost(cost::CostKind::kDissipation, press_then_drag_3d()));
  const Eigen::VectorXd x = body.initial_design();
  ASSERT_EQ(x.size(), 10);
  expect_strict(oracle, x);
  const Evaluation e = oracle.evaluate_design(x);
  ASSERT_TRUE(e.ok) << e.message;
  ASSERT_EQ(e.subgradient.size(), 10);
  const Eigen::VectorXd fd = oracle_central_gradient(oracle, x);
  const double error = (e.subgradient - fd).norm() / fd.norm();
  std::printf("dissipation with the orientation: dΘ/ds adjoint %.10e, FD %.10e; |ξ − FD|/|FD| = %.2e\n",
              e.subgradient(9), fd(9), error);
  EXPECT_GT(std::abs(fd(9)), 1e-6 * fd.norm());  // φ matters for this law and program
  EXPECT_LE(std::abs(e.subgradient(9) - fd(9)), 1e-6 * fd.norm());
  EXPECT_LE(error, 1e-6);
}

TEST(HistoryAdjoint, EachStepRecordsTheLawItWasSolvedWith) {
  // A frictionless press, then a drag with friction, the orientation a design variable: each
  // step's state carries the law it was solved with (W = {0}; the law turned to the design's φ),
  // which the index sets and the adjoint read; the definition keeps the user's law.
  const contact::FrictionLaw law = contact::FrictionLaw::regular_polygon(0.3, 8).rotated(0.1);
  BodyDefinition definition = pressed_block_3d(law);
  definition.friction_orientation = OrientationDesignDefinition{-1.5, 1.5};
  ElasticBody body(definition);
  auto program = std::make_shared<LoadingProgramDefinition>();
  program->steps = {step({}, {0.95, 0.0}, false), step({}, {1.0, 0.8})};
  ShapeOracle oracle(body, history_cost(cost::CostKind::kDissipation, program));
  Eigen::VectorXd x = body.initial_design();
  x(9) = body.orientation_design()->variable(0.7);
  const Evaluation& e = oracle.evaluate_design(x, false);
  ASSERT_TRUE(e.ok) << e.message;
  const ProgramHistory& history = *oracle.history();
  EXPECT_EQ(history.law(0).describe(), contact::frictionless_law(3).describe());
  EXPECT_NEAR(history.law(1).orientation(), 0.7, 1e-15);
  EXPECT_EQ(history.cost_state()->contact->law.get(), &history.law(1));
  EXPECT_EQ(body.definition().contact->law.orientation(), law.orientation());
}

TEST(HistoryAdjoint, AtAKinkEachOneSidedDerivativeIsAnEnumeratedSelections) {
  // Step 1 is the full load; step 2 unloads: on the flat bottom (α = 0, zero gaps) every contact
  // node of step 2 is weak (λ = 0, w = 0), so Θ (the target pressure after step 2) has a kink at
  // α, and a design that penetrates presses the nodes again with the slip reference of step 1.
  // Along a ray the selection of pieces is fixed for small t: the one-sided derivative is
  // ξ_(i1, i2)·h for some i2 ∈ 𝕃_2 (step 1 strict, its default piece).
  BodyDefinition def = frictopt::testing::thesis_body_2d(contact::FrictionLaw::interval(0.3, 0.3), 3, 2);
  def.initial_design = Eigen::VectorXd::Zero(def.shape.num_controls());
  def.admissible.volume.reset();  // α = 0 in Υ (on its lower bounds), for certify below
  auto program = std::make_shared<LoadingProgramDefinition>();
  program->steps = {step({1.0}, {}), step({0.0}, {})};
  CostDefinition cost = history_cost(cost::CostKind::kTargetPressure, program);
  cost.target_pressure = 1e6;
  ElasticBody body(def);
  ShapeOracle oracle(body, cost);
  const Eigen::VectorXd alpha = def.initial_design;
  const Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  ProgramHistory& h = *oracle.history();
  ASSERT_EQ(h.index_sets(0).num_weak_nodes(), 0) << h.index_sets(0).summary();
  ASSERT_GT(h.index_sets(1).num_weak_nodes(), 0) << h.index_sets(1).summary();
  const sensitivity::PieceEnumeration second = h.pieces(1, 4096);
  ASSERT_FALSE(second.sampled);
  std::printf("step 1: %s; step 2: %s, |L_2| = %.0f\n", h.index_sets(0).summary().c_str(),
              h.index_sets(1).summary().c_str(), second.cardinality);
  std::vector<Eigen::VectorXd> xi;
  for (const sensitivity::Piece& piece : second.pieces) {
    const HistorySubgradient r = h.subgradient({h.default_pieces()[0], piece});
    if (r.summary.status == Status::kConverged) xi.push_back(r.subgradient);
  }
  ASSERT_FALSE(xi.empty());
  std::mt19937_64 rng{frictopt::testing::kSeed};
  const double theta0 = e.value;
  int separated = 0;  // trials whose one-sided derivatives differ from the default ξ (a kink indeed)
  for (int trial = 0; trial < 6; ++trial) {
    const Eigen::VectorXd dir = frictopt::testing::random_direction(rng, alpha.size());
    const double t = 1e-6;
    const auto q = [&](double s) { return (oracle.evaluate_design(alpha + s * dir, false).value - theta0) / s; };
    const double quotient = 2.0 * q(0.5 * t) - q(t);  // Richardson: error O(t²) along the ray
    double best = std::numeric_limits<double>::infinity(), scale = std::abs(quotient);
    for (const Eigen::VectorXd& x : xi) {
      best = std::min(best, std::abs(x.dot(dir) - quotient));
      scale = std::max(scale, std::abs(x.dot(dir)));
    }
    separated += std::abs(e.subgradient.dot(dir) - quotient) > 1e-3 * scale;
    std::printf("trial %d: one-sided %.8e, default ξ·h %.8e, closest selection off by %.2e (relative %.2e)\n", trial,
                quotient, e.subgradient.dot(dir), best, best / scale);
    EXPECT_LE(best, 1e-6 * scale) << "no enumerated selection explains the one-sided derivative";
  }
  std::printf("%zu selections; %d of 6 directions are off the default ξ\n", xi.size(), separated);
  EXPECT_GT(separated, 0) << "no kink seen: the test would not detect a wrong selection";
  // certify: only step 2 has a choice, so its generators are all of 𝕃 = 𝕃_1 × 𝕃_2 (not sampled).
  // (Its classification is its own: at this degenerate state — λ = 0 up to the solver's
  // tolerance — a warm-started solve may see another node as weak than the cold one above.)
  CertifyOptions options;
  options.clarke_only = true;
  const Certificate c = certify(oracle, alpha, options);
  ASSERT_EQ(c.status, Status::kConverged) << c.message;
  std::printf("%s", c.report().c_str());
  EXPECT_FALSE(c.sampled);
  EXPECT_GT(c.cardinality, 1.0);
  EXPECT_EQ(static_cast<double>(c.subgradients.cols()), c.cardinality);
  ASSERT_EQ(c.history_steps.size(), 2u);
}

TEST(HistoryAdjoint, CertifyVariesOneStepAtATime) {
  ElasticBody body(pressed_block_3d(contact::FrictionLaw::regular_polygon(0.3, 8)));
  ShapeOracle oracle(body, history_cost(cost::CostKind::kDissipation, press_then_drag_3d()));
  const Eigen::VectorXd alpha = body.definition().initial_design;
  const Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  const Certificate c = certify(oracle, alpha);
  ASSERT_EQ(c.status, Status::kConverged) << c.message;
  std::printf("%s", c.report().c_str());
  // Strict in every step: one generator, the oracle's ξ; (MF1′) is not computed for a history.
  EXPECT_EQ(c.cardinality, 1.0);
  EXPECT_FALSE(c.sampled);
  ASSERT_EQ(c.subgradients.cols(), 1);
  EXPECT_LE((c.subgradients.col(0) - e.subgradient).norm(), 1e-12 * e.subgradient.norm());
  EXPECT_FALSE(c.mf1.computed);
  ASSERT_EQ(c.history_steps.size(), 2u);
  EXPECT_NE(c.report().find("loading history: 2 steps"), std::string::npos);
}

}  // namespace
}  // namespace frictopt::study
