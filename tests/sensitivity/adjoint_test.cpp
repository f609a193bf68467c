// SPDX-License-Identifier: MIT
// The adjoint subgradient against central differences of Θ where every index set is strict
// (spec 03, §17.1), for 2D and 3D, isotropic and anisotropic laws, and several costs.
#include "frictopt/sensitivity/adjoint.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "common/finite_difference.hpp"
#include "frictopt/cost/cost_functional.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::sensitivity {
namespace {

using frictopt::testing::kSeed;

// The thesis' 2D body (spec 05 §2.1, A-BC) on a coarse mesh, with the solver tolerances the
// finite differences need (the state error divided by the FD step must stay far below 1e-5).
study::BodyDefinition thesis_body_2d(const contact::FrictionLaw& law, int n1 = 20, int nv = 8) {
  study::BodyDefinition b;
  b.shape = shape::BezierShape::curve(2.0, 15);
  b.height = 1.0;
  b.resolution = {{n1, 0, nv}, 1.0};
  b.material = {1e9, 0.3, fem::PlaneModel::kPlaneStrain};
  b.dirichlet = {{mesh::Face::kLeft, {}, {}}};
  b.tractions = {{mesh::Face::kTop, Eigen::Vector2d(-8e7, -5e7)}};
  b.admissible.upper_bound = 0.75;
  b.admissible.height = 1.0;
  b.initial_design = Eigen::VectorXd::Constant(15, 0.05);
  study::ContactDefinition c;
  c.law = law;
  c.coulomb.relative_tolerance = 1e-14;
  c.coulomb.max_iterations = 200;
  c.coulomb.tresca.relative_tolerance = 1e-14;
  c.coulomb.tresca.max_iterations = 200000;
  b.contact = c;
  return b;
}

// A 3D block pressed by a rigid plate on its top (prescribed displacement), dish-shaped bottom.
study::BodyDefinition block_3d(const contact::FrictionLaw& law) {
  study::BodyDefinition b;
  b.shape = shape::BezierShape::surface(1.0, 1.0, 3, 3);
  b.height = 0.5;
  b.resolution = {{8, 8, 4}, 1.0};
  b.material = {7e10, 0.33, fem::PlaneModel::kPlaneStrain};
  b.dirichlet = {{mesh::Face::kTop, {}, Eigen::Vector3d(2e-4, 1e-4, -1.2e-3)}};
  b.admissible.upper_bound = 5e-3;
  b.admissible.height = 0.5;
  b.initial_design.resize(9);
  b.initial_design << 1.4e-3, 1.0e-3, 1.5e-3, 0.9e-3, 0.4e-3, 1.1e-3, 1.6e-3, 1.2e-3, 1.7e-3;
  study::ContactDefinition c;
  c.law = law;
  c.coulomb.relative_tolerance = 1e-14;
  c.coulomb.max_iterations = 200;
  c.coulomb.tresca.relative_tolerance = 1e-14;
  c.coulomb.tresca.max_iterations = 200000;
  b.contact = c;
  return b;
}

enum class CostKind { kTargetForce, kCompliance, kForcePower, kPressureNorm, kTotalSlip };

std::unique_ptr<cost::CostFunctional> make_cost(CostKind kind, study::ElasticBody& body) {
  switch (kind) {
    case CostKind::kTargetForce: {
      // Target: the initial total force spread evenly (spec 05 §2.3).
      const study::BodyState s = body.solve(body.definition().initial_design);
      const Eigen::VectorXd lambda = s.contact->state.normal_forces();
      return cost::make_target_normal_force(Eigen::VectorXd::Constant(lambda.size(), lambda.mean()));
    }
    case CostKind::kCompliance: return cost::make_compliance();
    case CostKind::kForcePower: return cost::make_normal_force_power(4.0);
    case CostKind::kPressureNorm: return cost::make_pressure_norm(6.0);
    case CostKind::kTotalSlip: return cost::make_total_slip(1e-6);
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
      {"Disc3D_Exact_Compliance", [] { return block_3d(contact::FrictionLaw::disc(0.3)); }, CostKind::kCompliance, {}},
      {"Ellipse3D_Exact_TotalSlip", [] { return block_3d(contact::FrictionLaw::ellipse(0.2, 0.4)); },
       CostKind::kTotalSlip, {}},
  };
}

INSTANTIATE_TEST_SUITE_P(Cases, SubgradientAtStrictPoints, ::testing::ValuesIn(gradient_cases()),
                         [](const auto& param_info) { return param_info.param.name; });

}  // namespace
}  // namespace frictopt::sensitivity
