// SPDX-License-Identifier: MIT
// The adjoint subgradient against central differences of Θ where every index set is strict
// (docs/sensitivity.md §5), for 2D and 3D, isotropic and anisotropic laws, and several costs.
#include "frictopt/sensitivity/adjoint.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "common/finite_difference.hpp"
#include "common/test_bodies.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/cost/cost_functional.hpp"
#include "frictopt/sensitivity/friction_parameters.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::sensitivity {
namespace {

using frictopt::testing::kSeed;

using frictopt::testing::format_vector;

study::BodyDefinition thesis_body_2d(const contact::FrictionLaw& law, int n1 = 20, int nv = 8) {
  return frictopt::testing::thesis_body_2d(law, n1, nv);
}

// A 3D block pressed by a rigid plate on its top (prescribed displacement), dish-shaped bottom.
study::BodyDefinition block_3d(const contact::FrictionLaw& law, Eigen::Vector2d shift = Eigen::Vector2d(2e-4, 1e-4)) {
  return frictopt::testing::dish_block_3d(law, Eigen::Vector3d(shift(0), shift(1), -1.2e-3));
}

enum class CostKind { kTargetForce, kCompliance, kForcePower, kPressureNorm, kTotalSlip, kTractionUniformity };

std::unique_ptr<cost::CostFunctional> make_cost(CostKind kind, study::ElasticBody& body) {
  switch (kind) {
    case CostKind::kTargetForce: {
      // Target: the initial total force spread evenly (docs/theory/costs.md).
      const study::BodyState s = body.solve(body.definition().initial_design);
      const Eigen::VectorXd lambda = s.contact->state.normal_forces();
      return cost::make_target_normal_force(Eigen::VectorXd::Constant(lambda.size(), lambda.mean()));
    }
    case CostKind::kCompliance: return cost::make_compliance();
    case CostKind::kForcePower: return cost::make_normal_force_power(4.0);
    case CostKind::kPressureNorm: return cost::make_pressure_norm(6.0);
    case CostKind::kTotalSlip: return cost::make_total_slip(1e-6);
    case CostKind::kTractionUniformity: return cost::make_traction_uniformity();
  }
  return nullptr;
}

struct GradientCase {
  std::string name;
  std::function<study::BodyDefinition()> body;
  CostKind cost;
  Eigen::VectorXd alpha;  // empty: the initial design
};

class SubgradientAtStrictPoints : public ::testing::TestWithParam<GradientCase> {};

TEST_P(SubgradientAtStrictPoints, MatchesCentralDifferences) {
  const GradientCase& c = GetParam();
  study::ElasticBody body(c.body());
  study::ShapeOracle oracle(body, make_cost(c.cost, body));
  const Eigen::VectorXd alpha = c.alpha.size() ? c.alpha : body.definition().initial_design;
  const study::Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  std::printf("%s: Θ = %.6e, %s; %s; %s\n", c.name.c_str(), e.value, e.index_sets.summary().c_str(),
              e.contact.brief_report().c_str(), e.adjoint.brief_report().c_str());
  ASSERT_EQ(e.index_sets.num_weak_nodes(), 0) << "the test point must be strict: " << e.index_sets.summary();
  const auto theta = [&](const Eigen::VectorXd& a) { return oracle.evaluate_design(a, false).value; };
  // Step: the design scale times 1e-4 keeps the truncation error (~h²·Θ''') below 1e-7 relative
  // while the state error (~1e-14·scale) divided by h stays below 1e-9.
  const double h = 1e-4 * alpha.cwiseAbs().maxCoeff();
  const Eigen::VectorXd fd = frictopt::testing::central_gradient(theta, alpha, h);
  const double error = (e.subgradient - fd).norm() / fd.norm();
  std::printf("%s: |ξ − FD|/|FD| = %.2e  (|ξ| = %.3e)\n", c.name.c_str(), error, fd.norm());
  for (Eigen::Index k = 0; k < alpha.size(); ++k)
    std::printf("   k=%2td  FD % .8e  adjoint % .8e\n", k, fd(k), e.subgradient(k));
  EXPECT_LE(error, 1e-5);
}

std::vector<GradientCase> gradient_cases() {
  return {
      {"Iso2D_TargetForce", [] { return thesis_body_2d(contact::FrictionLaw::interval(0.25, 0.25)); },
       CostKind::kTargetForce, {}},
      {"Iso2D_Compliance", [] { return thesis_body_2d(contact::FrictionLaw::interval(0.25, 0.25)); },
       CostKind::kCompliance, {}},
      {"Aniso2D_ForcePower", [] { return thesis_body_2d(contact::FrictionLaw::interval(0.15, 0.35)); },
       CostKind::kForcePower, {}},
      {"Iso3D_Polygon16_TargetForce", [] { return block_3d(contact::FrictionLaw::regular_polygon(0.3, 16)); },
       CostKind::kTargetForce, {}},
      {"Aniso3D_Polygon4_Compliance", [] { return block_3d(contact::FrictionLaw::polygon({0.2, 0.45, 0.2, 0.45})); },
       CostKind::kCompliance, {}},
      {"Ellipse3D_Polygon16_PressureNorm",
       [] { return block_3d(contact::FrictionLaw::ellipse_polygon(0.2, 0.4, 16)); }, CostKind::kPressureNorm, {}},
      {"StickCore3D_Polygon8_Compliance",
       [] { return block_3d(contact::FrictionLaw::regular_polygon(0.6, 8), Eigen::Vector2d(2e-6, 1e-6)); },
       CostKind::kCompliance, {}},
      {"StickCore3D_Disc_TargetForce",
       [] { return block_3d(contact::FrictionLaw::disc(0.6), Eigen::Vector2d(2e-6, 1e-6)); },
       CostKind::kTargetForce, {}},
      {"Disc3D_Exact_Compliance", [] { return block_3d(contact::FrictionLaw::disc(0.3)); }, CostKind::kCompliance, {}},
      {"Ellipse3D_Exact_TotalSlip", [] { return block_3d(contact::FrictionLaw::ellipse(0.2, 0.4)); },
       CostKind::kTotalSlip, {}},
      {"Aniso3D_Polygon4_TractionUniformity",
       [] { return block_3d(contact::FrictionLaw::polygon({0.2, 0.45, 0.2, 0.45})); }, CostKind::kTractionUniformity, {}},
      {"Aniso2D_TractionUniformity", [] { return thesis_body_2d(contact::FrictionLaw::interval(0.15, 0.35)); },
       CostKind::kTractionUniformity, {}},
  };
}

INSTANTIATE_TEST_SUITE_P(Cases, SubgradientAtStrictPoints, ::testing::ValuesIn(gradient_cases()),
                         [](const auto& param_info) { return param_info.param.name; });

}  // namespace
}  // namespace frictopt::sensitivity

namespace frictopt::sensitivity {
namespace {

// The state map y(α) = (u at the contact nodes, z) of the current piece, flattened.
Eigen::VectorXd contact_state_vector(study::ShapeOracle& oracle, const Eigen::VectorXd& alpha) {
  (void)oracle.evaluate_design(alpha, false);
  const study::BodyState& s = oracle.last_state();
  const contact::ContactBoundary& b = *oracle.body().contact_boundary();
  const int dim = b.dim();
  Eigen::VectorXd y(2 * b.num_unknowns());
  for (Eigen::Index i = 0; i < b.num_nodes(); ++i)
    for (int c = 0; c < dim; ++c) y(dim * i + c) = s.displacement(b.nodes()[static_cast<std::size_t>(i)] * dim + c);
  y.tail(b.num_unknowns()) = s.contact->state.z;
  return y;
}

Eigen::VectorXd flatten_derivative(study::ShapeOracle& oracle, const AdjointSensitivity::StateDerivative& d) {
  const contact::ContactBoundary& b = *oracle.body().contact_boundary();
  const int dim = b.dim();
  Eigen::VectorXd y(2 * b.num_unknowns());
  for (Eigen::Index i = 0; i < b.num_nodes(); ++i)
    for (int c = 0; c < dim; ++c) y(dim * i + c) = d.displacement(b.nodes()[static_cast<std::size_t>(i)] * dim + c);
  y.tail(b.num_unknowns()) = d.contact;
  return y;
}

// AdjointSensitivity::Options (Options in, Summary out): validated at construction;
// the default threshold is kSingularReciprocalCondition; a threshold above the piece's reciprocal
// condition turns the same solve into a reported failure.
TEST(AdjointOptions, AreValidatedAndTheSingularityThresholdIsApplied) {
  study::ElasticBody body(thesis_body_2d(contact::FrictionLaw::interval(0.25, 0.25), 12, 4));
  study::ShapeOracle oracle(body, cost::make_compliance());
  const Eigen::VectorXd alpha = body.definition().initial_design;
  const study::Evaluation e = oracle.evaluate_design(alpha);
  ASSERT_TRUE(e.ok) << e.message;
  const study::BodyState state = body.solve(alpha);  // the body's factorization is at α again
  ASSERT_TRUE(state.contact.has_value());
  const contact::ContactBoundary& boundary = *body.contact_boundary();
  const Eigen::MatrixXd gap_matrix = body.definition().shape.gap_matrix(boundary.plane_coordinates());
  const contact::FrictionLaw& law = body.definition().contact->law;
  CostPartials partials;  // any ∇_u J will do: the adjoint system's matrix does not depend on it

  partials.d_displacement = body.elasticity().traction_load(state.positions);

  AdjointSensitivity::Options bad;
  bad.singular_reciprocal_condition = -1e-3;
  EXPECT_THROW(AdjointSensitivity(body.elasticity(), boundary, gap_matrix, law, bad), InvalidInput);
  bad.singular_reciprocal_condition = 1.0;
  EXPECT_THROW(AdjointSensitivity(body.elasticity(), boundary, gap_matrix, law, bad), InvalidInput);

  const Piece piece = default_piece(e.index_sets);
  const AdjointSensitivity by_default(body.elasticity(), boundary, gap_matrix, law);
  EXPECT_EQ(by_default.options().singular_reciprocal_condition, kSingularReciprocalCondition);
  const auto reference = by_default.subgradient(piece, *state.contact->delassus, state.positions, state.displacement,
                                                state.contact->state, partials);
  ASSERT_EQ(reference.summary.status, Status::kConverged) << reference.summary.message;
  ASSERT_LT(reference.summary.reciprocal_condition, 0.5);

  AdjointSensitivity::Options strict;
  strict.singular_reciprocal_condition = 0.5;  // above this piece's rcond: "singular"
  const AdjointSensitivity strict_adjoint(body.elasticity(), boundary, gap_matrix, law, strict);
  const auto refused = strict_adjoint.subgradient(piece, *state.contact->delassus, state.positions, state.displacement,
                                                  state.contact->state, partials);
  EXPECT_EQ(refused.summary.status, Status::kNumericalFailure);
  EXPECT_EQ(refused.summary.reciprocal_condition, reference.summary.reciprocal_condition);
}

TEST(PieceJacobian, ColumnsMatchCentralDifferencesOfTheStateAtStrictPoints) {
  for (const bool three_d : {false, true}) {
    study::ElasticBody body(three_d ? block_3d(contact::FrictionLaw::polygon({0.2, 0.45, 0.2, 0.45}))
                                    : thesis_body_2d(contact::FrictionLaw::interval(0.15, 0.35)));
    study::ShapeOracle oracle(body, cost::make_compliance());
    const Eigen::VectorXd alpha = body.definition().initial_design;
    ASSERT_EQ(oracle.evaluate_design(alpha).index_sets.num_weak_nodes(), 0);
    std::mt19937_64 rng{kSeed};
    for (int trial = 0; trial < 3; ++trial) {
      const Eigen::VectorXd h = frictopt::testing::random_direction(rng, alpha.size());
      const AdjointSensitivity::StateDerivative derivative = oracle.state_derivative(alpha, h);
      ASSERT_EQ(derivative.status, Status::kConverged) << "rcond " << derivative.reciprocal_condition;
      const Eigen::VectorXd forward = flatten_derivative(oracle, derivative);
      const double eps = 1e-4 * alpha.cwiseAbs().maxCoeff();
      const Eigen::VectorXd fd =
          (contact_state_vector(oracle, alpha + eps * h) - contact_state_vector(oracle, alpha - eps * h)) / (2 * eps);
      // Displacements and forces have different units: compare each half relative to itself.
      const Eigen::Index m = fd.size() / 2;
      const double eu = (forward.head(m) - fd.head(m)).norm() / fd.head(m).norm();
      const double ez = (forward.tail(m) - fd.tail(m)).norm() / fd.tail(m).norm();
      std::printf("%s trial %d: R h vs FD: displacement %.2e, forces %.2e\n", three_d ? "3D" : "2D", trial, eu, ez);
      EXPECT_LE(eu, 1e-6);
      EXPECT_LE(ez, 1e-6);
    }
  }
}

TEST(IndexSets, ClassificationIsStableUnderSolverTolerance) {
  // Reference: block_3d's tight tolerances (1e-14, testing::tight_contact), solved once.
  const study::BodyDefinition reference = block_3d(contact::FrictionLaw::regular_polygon(0.3, 16));
  ASSERT_EQ(reference.contact->coulomb.tresca.relative_tolerance, 1e-14);
  study::ElasticBody reference_body(reference);
  const IndexSets expected = classify(reference_body.solve(reference.initial_design).contact->state, reference.contact->law);
  for (double tolerance : {1e-10, 1e-12}) {  // looser solves than the reference
    study::BodyDefinition def = reference;
    def.contact->coulomb.relative_tolerance = tolerance;
    def.contact->coulomb.tresca.relative_tolerance = tolerance;
    study::ElasticBody body(def);
    const study::BodyState s = body.solve(def.initial_design);
    const IndexSets sets = classify(s.contact->state, def.contact->law);
    ASSERT_EQ(sets.nodes.size(), expected.nodes.size());
    for (std::size_t i = 0; i < sets.nodes.size(); ++i) {
      EXPECT_EQ(sets.nodes[i].normal, expected.nodes[i].normal) << "node " << i << " tolerance " << tolerance;
      EXPECT_EQ(sets.nodes[i].tangential, expected.nodes[i].tangential) << "node " << i << " tolerance " << tolerance;
    }
    std::printf("tolerance %.0e: %s\n", tolerance, sets.summary().c_str());
  }
}

// A kink on purpose: zero gaps and no load make every contact node weakly in contact (I₀):
// the one-sided derivative along any direction must equal ξ_i·h for some enumerated piece.
study::BodyDefinition weak_contact_body(int dim) {
  study::BodyDefinition b = dim == 2 ? thesis_body_2d(contact::FrictionLaw::interval(0.3, 0.3), 3, 2)
                                     : block_3d(contact::FrictionLaw::polygon({0.2, 0.4, 0.2, 0.4}));
  if (dim == 3) {
    b.resolution = {{1, 1, 1}, 1.0};
    b.shape = shape::BezierShape::surface(1.0, 1.0, 2, 2);
    b.dirichlet = {{"left", {}, {}}};
  }
  b.tractions.clear();
  b.initial_design = Eigen::VectorXd::Zero(b.shape.num_controls());
  return b;
}

TEST(Subgradient, OneSidedDerivativeAtWeakContactMatchesAnEnumeratedPiece) {
  for (int dim : {2, 3}) {
    study::ElasticBody body(weak_contact_body(dim));
    const Eigen::VectorXd alpha = body.definition().initial_design;
    const auto p = body.contact_boundary()->num_nodes();
    // Target forces λ̄ ≠ 0 so that Θ = Σ(λ̄ − λ)² reacts to forces appearing.
    study::ShapeOracle oracle(body, cost::make_target_normal_force(Eigen::VectorXd::LinSpaced(p, 1e6, 2e6)));
    const study::Evaluation& e = oracle.evaluate_design(alpha);
    ASSERT_TRUE(e.ok) << e.message;
    EXPECT_EQ(e.index_sets.count(NormalSet::kWeakContact), p) << e.index_sets.summary();
    const PieceEnumeration pieces = oracle.pieces(alpha, 4096);
    ASSERT_FALSE(pieces.sampled) << "|L| = " << pieces.cardinality;
    std::vector<Eigen::VectorXd> xi;
    for (const auto& result : oracle.subgradients(alpha, pieces.pieces)) {
      ASSERT_EQ(result.summary.status, Status::kConverged) << result.summary.brief_report();
      xi.push_back(result.subgradient);
    }
    std::printf("dim %d: %s, |L| = %.0f\n", dim, e.index_sets.summary().c_str(), pieces.cardinality);
    std::mt19937_64 rng{kSeed};
    const double theta0 = e.value;
    for (int trial = 0; trial < 6; ++trial) {
      Eigen::VectorXd h = frictopt::testing::random_direction(rng, alpha.size());
      // Along a ray the piece is fixed for small t, so q(t) = Θ'(α;h) + c·t + O(t²): the
      // Richardson combination 2q(t/2) − q(t) removes the first-order error.
      const double t = 1e-7;
      const auto q = [&](double step) { return (oracle.evaluate_design(alpha + step * h, false).value - theta0) / step; };
      const double quotient = 2.0 * q(0.5 * t) - q(t);
      double best = std::numeric_limits<double>::infinity(), scale = std::abs(quotient);
      for (const Eigen::VectorXd& x : xi) {
        best = std::min(best, std::abs(x.dot(h) - quotient));
        scale = std::max(scale, std::abs(x.dot(h)));
      }
      std::printf("dim %d trial %d: one-sided quotient %.6e, closest ξ_i·h off by %.2e (relative %.2e)\n", dim,
                  trial, quotient, best, best / scale);
      // Extrapolated quotient: error O(t²); 1e-6 relative leaves room for the state tolerance.
      EXPECT_LE(best, 1e-6 * scale) << "no enumerated piece explains the one-sided derivative";
    }
  }
}

}  // namespace
}  // namespace frictopt::sensitivity

namespace frictopt::sensitivity {
namespace {

struct FrictionCase {
  std::string name;
  std::function<contact::FrictionLaw(const Eigen::VectorXd&)> make;  // from the parameters
  Eigen::VectorXd parameters;
  bool three_d;
};

class FrictionGradient : public ::testing::TestWithParam<FrictionCase> {};

TEST_P(FrictionGradient, MatchesCentralDifferencesInTheCoefficients) {
  const FrictionCase& c = GetParam();
  const auto body_for = [&](const Eigen::VectorXd& p) {
    return c.three_d ? block_3d(c.make(p)) : thesis_body_2d(c.make(p));
  };
  study::ElasticBody body(body_for(c.parameters));
  study::ShapeOracle oracle(body, cost::make_compliance());
  const study::Evaluation e = oracle.evaluate_design(body.definition().initial_design);
  ASSERT_TRUE(e.ok) << e.message;
  ASSERT_EQ(e.index_sets.num_weak_nodes(), 0) << e.index_sets.summary();
  ASSERT_EQ(friction_parameters(body.definition().contact->law).values.size(), c.parameters.size());
  EXPECT_LE((friction_parameters(body.definition().contact->law).values - c.parameters).norm(), 1e-12);
  const auto theta = [&](const Eigen::VectorXd& p) {
    study::ElasticBody b(body_for(p));
    study::ShapeOracle o(b, cost::make_compliance());
    return o.evaluate_design(b.definition().initial_design, false).value;
  };
  const Eigen::VectorXd fd = frictopt::testing::central_gradient(theta, c.parameters, 1e-5);
  const double error = (e.friction_gradient - fd).norm() / fd.norm();
  std::printf("%s: ∂Θ/∂μ adjoint %s vs FD %s: relative error %.2e\n", c.name.c_str(),
              format_vector(e.friction_gradient).c_str(), format_vector(fd).c_str(), error);
  EXPECT_LE(error, 1e-5);
}

INSTANTIATE_TEST_SUITE_P(
    Laws, FrictionGradient,
    ::testing::Values(
        FrictionCase{"Interval2D", [](const Eigen::VectorXd& p) { return contact::FrictionLaw::interval(p(0), p(1)); },
                     Eigen::Vector2d(0.15, 0.35), false},
        FrictionCase{"RegularPolygon3D",
                     [](const Eigen::VectorXd& p) { return contact::FrictionLaw::regular_polygon(p(0), 16); },
                     Eigen::VectorXd::Constant(1, 0.3), true},
        FrictionCase{"AnisotropicPolygon3D",
                     [](const Eigen::VectorXd& p) {
                       return contact::FrictionLaw::polygon({p(0), p(1), p(2), p(3)});
                     },
                     Eigen::Vector4d(0.2, 0.45, 0.25, 0.4), true},
        FrictionCase{"EllipsePolygon3D",
                     [](const Eigen::VectorXd& p) { return contact::FrictionLaw::ellipse_polygon(p(0), p(1), 16); },
                     Eigen::Vector2d(0.2, 0.4), true},
        FrictionCase{"Disc3D", [](const Eigen::VectorXd& p) { return contact::FrictionLaw::disc(p(0)); },
                     Eigen::VectorXd::Constant(1, 0.3), true},
        FrictionCase{"Ellipse3D", [](const Eigen::VectorXd& p) { return contact::FrictionLaw::ellipse(p(0), p(1)); },
                     Eigen::Vector2d(0.2, 0.4), true}),
    [](const auto& param_info) { return param_info.param.name; });

}  // namespace
}  // namespace frictopt::sensitivity
