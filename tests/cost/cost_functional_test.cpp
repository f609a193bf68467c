// SPDX-License-Identifier: MIT
// Every cost functional's value and partial gradients ∇_z J, ∇_u J, ∇_α J against central
// differences at a fixed, generic state (random z with λ > 0, random u) on small 2D and 3D bodies.
// The full chain through the state (ξ) is tested in tests/sensitivity/adjoint_test.cpp.
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "frictopt/contact/contact_boundary.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/cost/cost_functional.hpp"
#include "frictopt/cost/cost_kind.hpp"
#include "frictopt/fem/linear_elasticity.hpp"
#include "frictopt/mesh/structured_mesh.hpp"

namespace frictopt::cost {
namespace {

struct Body {
  explicit Body(int dim)
      : shape(dim == 3 ? shape::BezierShape::surface(1.0, 1.0, 2, 2) : shape::BezierShape::curve(1.0, 4)),
        mesh(mesh::StructuredMesh(shape, 0.5,
                                  dim == 3 ? mesh::GridResolution{{3, 3, 2}, 1.0} : mesh::GridResolution{{6, 0, 3}, 1.0})
                 .take_mesh()),
        fem(mesh, {1e9, 0.3, fem::PlaneModel::kPlaneStrain}, fem::expand_dirichlet(mesh, {{"left", {}, {}}}),
            {{"top", dim == 3 ? Eigen::VectorXd(Eigen::Vector3d(1e6, -2e6, -5e6))
                                         : Eigen::VectorXd(Eigen::Vector2d(1e6, -5e6))}}),
        boundary(mesh, fem.dofs()) {
    std::mt19937 rng(dim);
    std::uniform_real_distribution<double> unit(0.2, 1.0);
    alpha = Eigen::VectorXd(shape.num_controls());
    for (Eigen::Index k = 0; k < alpha.size(); ++k) alpha(k) = 0.02 * unit(rng);
    displacement = Eigen::VectorXd(fem.dofs().num_dofs());
    for (Eigen::Index k = 0; k < displacement.size(); ++k) displacement(k) = 1e-3 * (unit(rng) - 0.6);
    state = contact::ContactState(dim, boundary.num_nodes());
    for (Eigen::Index k = 0; k < state.z.size(); ++k)
      state.z(k) = (k % dim == dim - 1) ? 1e5 * unit(rng) : 3e4 * (unit(rng) - 0.6);  // λ > 0, q of both signs
  }

  sensitivity::CostPartials evaluate(const CostFunctional& cost) const {
    const Eigen::MatrixXd X = mesh.positions(alpha);
    return cost.evaluate({fem, boundary, alpha, X, displacement, state, boundary.tributary_areas()});
  }

  shape::BezierShape shape;
  mesh::Mesh mesh;
  fem::LinearElasticity fem;
  contact::ContactBoundary boundary;
  Eigen::VectorXd alpha, displacement;
  contact::ContactState state;
};

/// max_k |FD_k − g_k| / max(‖g‖_∞, tiny) for J along each coordinate of `x`.
double fd_error(Body& body, const CostFunctional& cost, Eigen::VectorXd& x, const Eigen::VectorXd& gradient) {
  double worst = 0.0;
  const double scale = std::max(gradient.cwiseAbs().maxCoeff(), 1e-300);
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    const double x0 = x(k), h = 1e-6 * std::max(std::abs(x0), 1e-3 * x.cwiseAbs().maxCoeff());
    x(k) = x0 + h;
    const double plus = body.evaluate(cost).value;
    x(k) = x0 - h;
    const double minus = body.evaluate(cost).value;
    x(k) = x0;
    worst = std::max(worst, std::abs((plus - minus) / (2 * h) - gradient(k)) / scale);
  }
  return worst;
}

struct CostCase {
  std::string name;
  int dim;
  std::function<std::unique_ptr<CostFunctional>(const Body&)> make;
};

class CostGradients : public ::testing::TestWithParam<CostCase> {};

TEST_P(CostGradients, PartialsMatchCentralDifferences) {
  Body body(GetParam().dim);
  const auto cost = GetParam().make(body);
  const sensitivity::CostPartials j = body.evaluate(*cost);
  ASSERT_TRUE(std::isfinite(j.value));
  ASSERT_EQ(j.d_contact.size(), body.state.z.size());
  ASSERT_EQ(j.d_displacement.size(), body.displacement.size());
  ASSERT_EQ(j.d_alpha.size(), body.alpha.size());
  EXPECT_GT(j.d_contact.norm() + j.d_displacement.norm() + j.d_alpha.norm(), 0.0);
  EXPECT_LE(fd_error(body, *cost, body.state.z, j.d_contact), 1e-6) << "d/dz";
  EXPECT_LE(fd_error(body, *cost, body.displacement, j.d_displacement), 1e-6) << "d/du";
  EXPECT_LE(fd_error(body, *cost, body.alpha, j.d_alpha), 1e-6) << "d/dα";
}

std::unique_ptr<CostFunctional> target_force(const Body& b) {
  return make_target_normal_force(Eigen::VectorXd::LinSpaced(b.boundary.num_nodes(), 2e4, 9e4));
}

INSTANTIATE_TEST_SUITE_P(
    AllCosts, CostGradients,
    ::testing::Values(
        CostCase{"TargetNormalForce3D", 3, target_force}, CostCase{"TargetNormalForce2D", 2, target_force},
        CostCase{"NormalForcePower3D", 3, [](const Body&) { return make_normal_force_power(4.0); }},
        CostCase{"Compliance3D", 3, [](const Body&) { return make_compliance(); }},
        CostCase{"Compliance2D", 2, [](const Body&) { return make_compliance(); }},
        CostCase{"PressureNorm3D", 3, [](const Body&) { return make_pressure_norm(8.0); }},
        CostCase{"TotalSlip3D", 3, [](const Body&) { return make_total_slip(1e-6); }},
        CostCase{"TotalSlip2D", 2, [](const Body&) { return make_total_slip(1e-6); }},
        CostCase{"TractionUniformityMean3D", 3, [](const Body&) { return make_traction_uniformity(); }},
        CostCase{"TractionUniformityMean2D", 2, [](const Body&) { return make_traction_uniformity(); }},
        CostCase{"TractionUniformityTarget3D", 3,
                 [](const Body&) { return make_traction_uniformity(Eigen::Vector2d(-4e4, 1e4)); }},
        CostCase{"TractionUniformityTarget2D", 2,
                 [](const Body&) { return make_traction_uniformity(Eigen::VectorXd::Constant(1, 2e4)); }}),
    [](const auto& param_info) { return param_info.param.name; });

// A cost is printed (console, pictures, summary.json's "cost" next to "cost_kind") under the
// case file's kind: target_pressure's functional was once named "target_normal_force".
TEST(CostNames, AreTheCaseFileKinds) {
  const Body body(3);
  EXPECT_EQ(target_force(body)->name(), to_string(CostKind::kTargetPressure));
  EXPECT_EQ(make_normal_force_power(4.0)->name(), to_string(CostKind::kNormalForcePower));
  EXPECT_EQ(make_compliance()->name(), to_string(CostKind::kCompliance));
  EXPECT_EQ(make_pressure_norm(8.0)->name(), to_string(CostKind::kPressureNorm));
  EXPECT_EQ(make_total_slip(1e-6)->name(), to_string(CostKind::kTotalSlip));
  EXPECT_EQ(make_traction_uniformity()->name(), to_string(CostKind::kTractionUniformity));
}

TEST(TractionUniformity, IsTheAreaWeightedVarianceAndZeroForAUniformTraction) {
  Body body(3);
  const Eigen::VectorXd& a = body.boundary.tributary_areas();
  const Eigen::Vector2d t(3e4, -1e4);  // a uniform traction: τ_i = t a_i, q_i = −τ_i
  for (Eigen::Index i = 0; i < a.size(); ++i) body.state.z.segment(3 * i, 2) = -t * a(i);
  EXPECT_LE(body.evaluate(*make_traction_uniformity()).value, 1e-20 * t.squaredNorm() * a.sum());
  // About a target t̄: J = Σ a_i ‖t − t̄‖² = A ‖t − t̄‖².
  const Eigen::Vector2d target(1e4, 1e4);
  EXPECT_NEAR(body.evaluate(*make_traction_uniformity(target)).value, a.sum() * (t - target).squaredNorm(),
              1e-12 * a.sum() * (t - target).squaredNorm());
}

TEST(TractionUniformity, TargetOfTheWrongDimensionIsAClearError) {
  Body body(2);
  try {
    (void)body.evaluate(*make_traction_uniformity(Eigen::Vector2d(1.0, 2.0)));
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("expected 1 for a 2D body"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)make_traction_uniformity(Eigen::Vector3d(1, 2, 3)), InvalidInput);
}

}  // namespace
}  // namespace frictopt::cost
