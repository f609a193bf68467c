// SPDX-License-Identifier: MIT
// The friction law's orientation φ as a design variable (docs/theory/
// friction-design.md): ∂Θ/∂s from the adjoint against central differences of Θ at strict index
// sets for the anisotropic 3D laws; the full x = (α, s) gradient check; a fixed φ = φ⁰ gives
// the plain oracle's numbers bit for bit and the oracle's cache follows φ; certify's generators
// and a short optimization carry the φ component; bad input names the field (exit 2).
#include "frictopt/study/orientation_design.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "common/case_text.hpp"
#include "common/invalid_case.hpp"
#include "common/test_bodies.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/study/certificate.hpp"
#include "frictopt/study/gradient_check.hpp"
#include "frictopt/study/shape_optimization.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::study {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// A 3D block pressed and dragged by a rigid plate on its top, with a dish-shaped bottom (as the
// sensitivity tests' block): stick and slip nodes occur, the tangential drag makes the traction
// depend on how the law is turned.
BodyDefinition block_3d(const contact::FrictionLaw& law, bool orientation_design) {
  BodyDefinition b = frictopt::testing::dish_block_3d(law, Eigen::Vector3d(2e-4, 1e-4, -1.2e-3));
  if (orientation_design) b.friction_orientation = OrientationDesignDefinition{-90 * kDegree, 90 * kDegree};
  return b;
}

// The traction variance: it reads the tangential forces, which the orientation moves directly.
CostDefinition traction_cost() {
  CostDefinition d;
  d.kind = cost::CostKind::kTractionUniformity;
  return d;
}

struct LawCase {
  std::string name;
  contact::FrictionLaw law;  // unturned; the tests turn it by φ⁰ = 0.4 rad
};

class OrientationDesignDerivative : public ::testing::TestWithParam<LawCase> {};

// ∂Θ/∂s (the last ξ component) against (Θ(s + h) − Θ(s − h))/2h with h = k·1e-6 rad: the
// piece is fixed for small steps where the index sets are strict, so the quotient is exact up
// to O(h²) and the state tolerance (1e-14): ~1e-8 relative is expected, 1e-6 is the bound.
TEST_P(OrientationDesignDerivative, MatchesCentralDifferencesAtStrictIndexSets) {
  const LawCase& c = GetParam();
  ElasticBody body(block_3d(c.law.rotated(0.4), true));
  ShapeOracle oracle(body, traction_cost());
  const Eigen::VectorXd x = body.initial_design();
  ASSERT_EQ(x.size(), 10);
  const Evaluation e = oracle.evaluate_design(x);
  ASSERT_TRUE(e.ok) << e.message;
  ASSERT_EQ(e.index_sets.num_weak_nodes(), 0) << e.index_sets.summary();
  ASSERT_EQ(e.subgradient.size(), 10);
  const double k = body.orientation_design()->scale();
  const double h = k * 1e-6;
  Eigen::VectorXd plus = x, minus = x;
  plus(9) += h;
  minus(9) -= h;
  const double fd = (oracle.evaluate_design(plus, false).value - oracle.evaluate_design(minus, false).value) / (2 * h);
  const double error = std::abs(e.subgradient(9) - fd) / std::abs(fd);
  std::printf("%s: dTheta/dphi adjoint %.10e, central difference %.10e, relative error %.2e (%s)\n", c.name.c_str(),
              e.subgradient(9) * k, fd * k, error, e.index_sets.summary().c_str());
  EXPECT_GT(std::abs(fd) * k, 1e-3 * std::abs(e.value)) << "the orientation should matter for this cost";
  EXPECT_LE(error, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(
    Laws, OrientationDesignDerivative,
    ::testing::Values(LawCase{"FourGon", contact::FrictionLaw::regular_polygon(0.3, 4)},
                      LawCase{"PerVertexPolygon", contact::FrictionLaw::polygon({0.4, 0.2, 0.4, 0.2})},
                      LawCase{"Ellipse", contact::FrictionLaw::ellipse(0.2, 0.4)},
                      LawCase{"EllipsePolygon", contact::FrictionLaw::ellipse_polygon(0.2, 0.4, 16)}),
    [](const auto& test_case) { return test_case.param.name; });

// The whole ξ = (ξ_α, ∂Θ/∂s) against central differences (what `frictopt check-gradient` prints).
TEST(OrientationDesign, FullGradientMatchesCentralDifferences) {
  ElasticBody body(block_3d(contact::FrictionLaw::polygon({0.4, 0.2, 0.4, 0.2}).rotated(0.4), true));
  ShapeOracle oracle(body, traction_cost());
  // h_k = 3e-6 × the width of x_k's bounds: 1.5e-8 m for the heights (C0 = 5 mm), as small as
  // 1e-5·max|x| was before steps were scaled by the bounds; at 5e-8 m nodes change piece.
  const GradientCheck check = check_gradient(oracle, body.initial_design(), 3e-6);
  ASSERT_TRUE(check.evaluation.ok) << check.evaluation.message;
  ASSERT_EQ(check.evaluation.index_sets.num_weak_nodes(), 0);
  ASSERT_EQ(check.components.size(), 10u);
  for (std::size_t i = 0; i < check.components.size(); ++i)
    std::printf("x[%zu]: FD %.8e adjoint %.8e rel %.2e\n", i, check.components[i].finite_difference,
                check.components[i].adjoint, check.components[i].relative_error);
  EXPECT_LE(check.worst_relative_error, 1e-5);
  EXPECT_LE(check.components.back().relative_error, 1e-6);
  // At h = 5e-8 m (relative 1e-5) strict index sets at x do not keep every node on its piece:
  // the components whose central quotient misses ξ (up to 2 %, "weak nodes 0") are those where
  // a node changes piece within ±h, and ξ_k is then a one-sided quotient (a kink, not a bug).
  const GradientCheck wide = check_gradient(oracle, body.initial_design(), 1e-5);
  int kinks = 0;
  for (std::size_t i = 0; i < wide.components.size(); ++i) {
    const auto& c = wide.components[i];
    EXPECT_NE(c.verdict, GradientCheck::Verdict::kMismatch) << "x[" << i << "] rel " << c.relative_error;
    kinks += c.verdict == GradientCheck::Verdict::kKink;
  }
  EXPECT_GT(kinks, 0);
}

// At φ = φ⁰ the orientation design solves the case's own law: the same Θ and ξ_α as the plain
// oracle, bit for bit. The cache follows φ: a new φ at the same α is solved again (not the cached
// value), and returning to φ⁰ gives the first numbers again.
TEST(OrientationDesign, FixedAngleIsThePlainOracleAndTheCacheFollowsTheAngle) {
  const contact::FrictionLaw law = contact::FrictionLaw::ellipse(0.2, 0.4).rotated(0.4);
  ElasticBody plain_body(block_3d(law, false)), body(block_3d(law, true));
  ShapeOracle plain(plain_body, traction_cost()), oracle(body, traction_cost());
  const Evaluation a = plain.evaluate_design(plain_body.initial_design());
  const Eigen::VectorXd x = body.initial_design();
  const Evaluation b = oracle.evaluate_design(x);
  ASSERT_TRUE(a.ok && b.ok) << a.message << b.message;
  EXPECT_EQ(a.value, b.value);
  ASSERT_EQ(b.subgradient.size(), a.subgradient.size() + 1);
  EXPECT_EQ((a.subgradient - b.subgradient.head(a.subgradient.size())).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_DOUBLE_EQ(body.orientation_design()->angle(x(9)), 0.4);

  Eigen::VectorXd turned = x;
  turned(9) = body.orientation_design()->variable(0.9);
  const Evaluation c = oracle.evaluate_design(turned);
  ASSERT_TRUE(c.ok) << c.message;
  EXPECT_NE(c.value, b.value) << "a new orientation must be solved, not answered from the α-keyed state";
  // The state records the law it was solved with; the definition stays the user's input.
  EXPECT_NEAR(oracle.last_state().contact->law->orientation(), 0.9, 1e-15);
  EXPECT_EQ(body.definition().contact->law.orientation(), 0.4);
  // A fresh oracle at the turned design (its law as the case's own) agrees to the solver's tolerance.
  ElasticBody turned_body(block_3d(law.rotated(0.5), false));
  ShapeOracle turned_plain(turned_body, traction_cost());
  const Evaluation d = turned_plain.evaluate_design(turned_body.initial_design());
  EXPECT_NEAR(c.value, d.value, 1e-9 * std::abs(d.value));
  // Back at φ⁰ after a solve elsewhere, its state solved again: the law is the case's own.
  const int solves = oracle.num_state_solves();
  (void)oracle.subgradients(x, {});  // re-solves at x (the last state is at `turned`)
  EXPECT_EQ(oracle.num_state_solves(), solves + 1);
  EXPECT_EQ(oracle.last_state().contact->law->orientation(), 0.4) << "each state keeps its own law";
  // Warm-started from the turned state: the same solution to the solver's tolerance (1e-14).
  const Eigen::VectorXd& z = oracle.last_state().contact->state.z;
  EXPECT_LE((z - plain.last_state().contact->state.z).norm(), 1e-9 * z.norm());
}

// Load cases (docs/theory/load-cases.md): each case's ξ_k gets its own φ-component from its own
// ψ_z and the weighted sum carries it; against central differences of the combined Θ.
TEST(OrientationDesign, LoadCasesSumTheOrientationComponent) {
  ElasticBody body(block_3d(contact::FrictionLaw::polygon({0.4, 0.2, 0.4, 0.2}).rotated(0.4), true));
  CostDefinition cost = traction_cost();
  LoadCaseDefinition press, deeper;
  press.name = "press";
  press.dirichlet_scale = {1.0};
  deeper.name = "deeper";
  deeper.dirichlet_scale = {1.3};
  deeper.weight = 0.5;
  cost.load_cases = LoadCasesDefinition{CaseCombination::kWeighted, {press, deeper}};
  ShapeOracle oracle(body, cost);
  const Eigen::VectorXd x = body.initial_design();
  const GradientCheck check = check_gradient(oracle, x, 1e-6);
  ASSERT_TRUE(check.evaluation.ok) << check.evaluation.message;
  for (int k = 0; k < 2; ++k) ASSERT_EQ(oracle.program(x, k).cost_step_index_sets().num_weak_nodes(), 0);
  ASSERT_EQ(check.evaluation.case_values.size(), 2u);
  std::printf("load cases: dTheta/ds adjoint %.10e, central difference %.10e; worst error %.2e of max|xi|\n",
              check.components.back().adjoint, check.components.back().finite_difference, check.worst_relative_error);
  EXPECT_LE(std::abs(check.components.back().adjoint - check.components.back().finite_difference),
            1e-6 * std::abs(check.components.back().finite_difference));
  EXPECT_LE(check.worst_relative_error, 1e-5);
}

// certify's generators have the φ row; the default piece's column is the oracle's ξ.
TEST(OrientationDesign, CertifyGeneratorsCarryTheOrientationComponent) {
  ElasticBody body(block_3d(contact::FrictionLaw::regular_polygon(0.3, 4).rotated(0.4), true));
  ShapeOracle oracle(body, traction_cost());
  const Eigen::VectorXd x = body.initial_design();
  CertifyOptions options;
  options.cap = 8;
  const Certificate c = certify(oracle, x, options);
  ASSERT_EQ(c.status, Status::kConverged) << c.message;
  ASSERT_EQ(c.subgradients.rows(), 10);
  const Evaluation& e = oracle.evaluate_design(x);
  ASSERT_TRUE(e.ok);
  EXPECT_NEAR(c.subgradients(9, c.default_piece_column), e.subgradient(9), 1e-12 * e.subgradient.norm());
  EXPECT_NE(c.subgradients(9, c.default_piece_column), 0.0);
}

// A few bundle iterations move φ within its bounds and decrease Θ.
TEST(OrientationDesign, OptimizationMovesTheAngleWithinItsBounds) {
  ElasticBody body(block_3d(contact::FrictionLaw::polygon({0.4, 0.2, 0.4, 0.2}).rotated(0.4), true));
  ShapeOracle oracle(body, traction_cost());
  optim::BundleTrust::Options options = default_study_options(body.definition());
  options.max_iterations = 4;
  options.certify_stationarity = false;
  const optim::BundleTrust::Summary s = optimize(oracle, options, nullptr);
  ASSERT_EQ(s.x.size(), 10);
  const double phi = body.orientation_design()->angle(s.x(9));
  std::printf("Θ %.6e -> %.6e, φ 0.4 -> %.6f rad\n", oracle.evaluate_design(body.initial_design()).value, s.f, phi);
  EXPECT_LT(s.f, oracle.evaluate_design(body.initial_design()).value);
  EXPECT_NE(phi, 0.4);
  EXPECT_GE(phi, -90 * kDegree - 1e-12);
  EXPECT_LE(phi, 90 * kDegree + 1e-12);
}

// Programmatic bad input: the body refuses it before any solve, naming the field.
TEST(OrientationDesign, BodyRefusesLawsWithoutAnOrientationThatMatters) {
  const auto refused = [](const BodyDefinition& b, const std::string& fragment) {
    try {
      ElasticBody body(b);
      ADD_FAILURE() << "accepted; expected '" << fragment << "'";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  refused(block_3d(contact::FrictionLaw::disc(0.3), true), "isotropic");
  refused(block_3d(contact::FrictionLaw::ellipse(0.3, 0.3), true), "isotropic");
  BodyDefinition reversed = block_3d(contact::FrictionLaw::ellipse(0.2, 0.4), true);
  reversed.friction_orientation = OrientationDesignDefinition{0.5, -0.5};
  refused(reversed, "orientation_lower_deg");
  BodyDefinition outside = block_3d(contact::FrictionLaw::ellipse(0.2, 0.4).rotated(1.0), true);
  outside.friction_orientation = OrientationDesignDefinition{-0.5, 0.5};
  refused(outside, "orientation_deg");
  BodyDefinition two_d = frictopt::testing::thesis_body_2d();
  two_d.friction_orientation = OrientationDesignDefinition{-0.5, 0.5};
  refused(two_d, "2D interval law has no orientation");
}

// The case file's keys: each bad input names its field (the CLI exits 2 on InvalidInput).
const std::string kCase3d = frictopt::testing::block_header_3d("1.0", "0.5") +
                            frictopt::testing::top_dirichlet("[1.0e-4, 0.0, -1.2e-3]") +
                            frictopt::testing::design_table("[3, 3]", "1.0e-3", "5.0e-3") + R"(friction_orientation = true
orientation_lower_deg = -60
orientation_upper_deg = 60
[contact.friction]
kind = "ellipse"
mu_x = 0.2
mu_y = 0.4
orientation_deg = 20
[cost]
kind = "traction_uniformity"
)";

TEST(OrientationDesign, CaseFileKeys) {
  const io::CaseDescription c = io::parse_case(kCase3d, "case.toml");
  ASSERT_TRUE(c.body.friction_orientation);
  EXPECT_DOUBLE_EQ(c.body.friction_orientation->lower, -60 * kDegree);
  EXPECT_DOUBLE_EQ(c.body.friction_orientation->upper, 60 * kDegree);
  ElasticBody body(c.body);
  EXPECT_EQ(body.num_design_variables(), 10);
  EXPECT_EQ(body.admissible_set().dimension(), 10);
  // k = C0 / (φ_max − φ_min): the range of s is C0 long, as each α_k's.
  EXPECT_NEAR(body.admissible_set().upper(9) - body.admissible_set().lower(9), 5e-3, 1e-15);
  EXPECT_NEAR(body.orientation_design()->angle(body.initial_design()(9)), 20 * kDegree, 1e-15);
}

TEST(OrientationDesign, CaseFileBadInputNamesTheField) {
  using frictopt::testing::expect_invalid_case;
  using frictopt::testing::replaced;
  const std::string base = kCase3d;
  expect_invalid_case(replaced(base, "kind = \"ellipse\"\nmu_x = 0.2\nmu_y = 0.4", "kind = \"disc_exact\"\nmu = 0.3"),
                      {"friction_orientation", "isotropic"});
  expect_invalid_case(replaced(base, "orientation_upper_deg = 60", "orientation_upper_deg = -70"),
                      {"orientation_upper_deg"});
  expect_invalid_case(replaced(base, "orientation_deg = 20", "orientation_deg = 70"),
                      {"orientation_deg", "outside the design bounds"});
  expect_invalid_case(replaced(base, "orientation_lower_deg = -60\n", ""), {"orientation_lower_deg", "missing"});
  expect_invalid_case(replaced(base, "[cost]", "[solver]\nengine = \"petsc\"\n[cost]"),
                      {"friction_orientation", "PETSc", "engine = \"direct\""});
  expect_invalid_case(replaced(base, "friction_orientation = true", "friction_orientation = false"),
                      {"orientation_lower_deg", "without friction_orientation"});
}

}  // namespace
}  // namespace frictopt::study
