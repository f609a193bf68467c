// SPDX-License-Identifier: MIT
// Floating bodies (docs/experiments.md §5): a block with no Dirichlet condition,
// pressed by a top pressure and pulled by a tangential traction, held only by contact and
// friction. Inside the friction capacity the solve reaches equilibrium: the reaction at every DOF
// off the contact surface (including the DOFs held for A⁺) vanishes, and the contact forces
// balance the loads; outside, the report "the tangential force … exceeds the friction capacity
// μ(θ)·P … by x %", never a silent or diverged result.
#include "frictopt/study/floating_body.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "frictopt/core/error.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/loading_program.hpp"

namespace frictopt::study {
namespace {

using contact::FrictionLaw;

// A 0.1 m × 0.1 m × 0.05 m block on the foundation (flat bottom), no Dirichlet condition: a
// pressure p on the top and a tangential traction (t1, t2) on the top.
BodyDefinition floating_block(const FrictionLaw& law, double pressure,
                              const Eigen::Vector2d& shear) {
  BodyDefinition b;
  b.shape = shape::BezierShape::surface(0.1, 0.1, 2, 2);
  b.height = 0.05;
  b.resolution = {{6, 6, 3}, 1.0};
  b.material = {7e10, 0.33, fem::PlaneModel::kPlaneStrain};
  b.tractions = {{"top", Eigen::Vector3d(shear(0), shear(1), -pressure)}};
  b.admissible.upper_bound = 1e-3;
  b.admissible.height = 0.05;
  b.initial_design = Eigen::VectorXd::Zero(4);
  ContactDefinition c;
  c.law = law;
  c.coulomb.relative_tolerance = 1e-12;
  c.coulomb.tresca.relative_tolerance = 1e-12;
  b.contact = c;
  return b;
}

// The reaction A_full u − l at every DOF: the contact forces at the contact DOFs, the support's
// reaction at the DOFs the Dirichlet conditions prescribe, zero elsewhere (in particular at the
// DOFs held to factorize the stiffness).
double relative_imbalance_off_contact(const ElasticBody& body, const BodyState& s) {
  const Eigen::VectorXd r = body.elasticity().residual(s.positions, s.displacement);
  const Eigen::VectorXd l = body.elasticity().traction_load(s.positions);
  std::vector<char> contact(static_cast<std::size_t>(body.mesh().num_dofs()), 0);
  for (int node : body.contact_boundary()->nodes())
    for (int c = 0; c < 3; ++c) contact[static_cast<std::size_t>(3 * node + c)] = 1;
  for (int d : fem::expand_dirichlet(body.mesh(), body.definition().dirichlet).dofs)
    contact[static_cast<std::size_t>(d)] = 1;
  double worst = 0.0;
  for (Eigen::Index d = 0; d < r.size(); ++d)
    if (!contact[static_cast<std::size_t>(d)]) worst = std::max(worst, std::abs(r(d)));
  return worst / std::max(l.cwiseAbs().maxCoeff(), r.cwiseAbs().maxCoeff());
}

TEST(FloatingBody, InsideTheCapacityTheContactBalancesTheLoads) {
  const double p = 1e6;  // Pa on 0.01 m²: P = 10 kN
  for (const auto& [name, law, shear] :
       {std::tuple{std::string("disc 0.3"), FrictionLaw::disc(0.3), Eigen::Vector2d(1.5e5, 0.0)},
        std::tuple{std::string("4-gon (0.4, 0.2)"), FrictionLaw::polygon({0.4, 0.2, 0.4, 0.2}),
                   Eigen::Vector2d(1e5, 1e5)},
        std::tuple{std::string("ellipse (0.4, 0.2)"), FrictionLaw::ellipse(0.4, 0.2),
                   Eigen::Vector2d(0.0, 1.5e5)}}) {
    SCOPED_TRACE(name);
    ElasticBody body(floating_block(law, p, shear));
    EXPECT_EQ(body.num_floating_modes(), 6);
    const BodyState s = body.solve(body.definition().initial_design);
    ASSERT_EQ(s.summary.status, Status::kConverged) << s.summary.brief_report() << "\n"
                                                    << s.contact->floating->brief_report();
    const auto& res = s.contact->resultants;
    const double imbalance = relative_imbalance_off_contact(body, s);
    std::printf(
        "%s: P = %.9e N, T = (%.6e, %.6e) N, stick %d slip %d, imbalance off Γ_c %.1e, %s\n",
        name.c_str(), res.normal_force, res.tangential_force(0), res.tangential_force(1),
        res.num_stick, res.num_slip, imbalance, s.contact->floating->brief_report().c_str());
    // Zero net force residual: the contact forces balance the loads, and no reaction is left at
    // the DOFs held to factorize the stiffness (relative to the largest nodal load).
    EXPECT_LE(imbalance, 1e-7);
    EXPECT_NEAR(res.normal_force, p * 0.01, 1e-7 * p * 0.01);
    EXPECT_NEAR(-res.tangential_force(0), shear(0) * 0.01, 1e-7 * p * 0.01);
    EXPECT_NEAR(-res.tangential_force(1), shear(1) * 0.01, 1e-7 * p * 0.01);
    EXPECT_GT(res.num_stick, 0);
  }
}

TEST(FloatingBody, BeyondTheCapacityReportsTheExcess) {
  ElasticBody body(
      floating_block(FrictionLaw::disc(0.3), 1e6, Eigen::Vector2d(3.6e5, 0.0)));  // 1.2 μ P
  const BodyState s = body.solve(body.definition().initial_design);
  EXPECT_NE(s.summary.status, Status::kConverged);
  EXPECT_NE(s.summary.message.find("exceeds the friction capacity"), std::string::npos)
      << s.summary.message;
  EXPECT_NE(s.summary.message.find("by 20 %"), std::string::npos) << s.summary.message;
  // The anisotropic law's capacity depends on the direction: 0.3·P along x1 fits the 4-gon
  // (μ(0°) ≈ 0.27 … ) or not, as its radial function says.
  const FrictionLaw rhombus = FrictionLaw::polygon({0.4, 0.2, 0.4, 0.2});
  const double mu0 = rhombus.max_step(Eigen::Vector2d::Zero(), 1.0, Eigen::Vector2d(1.0, 0.0));
  ElasticBody over(floating_block(rhombus, 1e6, Eigen::Vector2d(1.1 * mu0 * 1e6, 0.0)));
  const BodyState so = over.solve(over.definition().initial_design);
  EXPECT_NE(so.summary.message.find("by 10 %"), std::string::npos) << so.summary.message;
  ElasticBody under(floating_block(rhombus, 1e6, Eigen::Vector2d(0.9 * mu0 * 1e6, 0.0)));
  EXPECT_EQ(under.solve(under.definition().initial_design).summary.status, Status::kConverged);
}

// Pressed by a prescribed vertical displacement of the top (x1, x2 and the rotation about x3 stay
// free): P is a result, so the capacity is checked after the iteration, at the last P.
TEST(FloatingBody, DisplacementPressedBlockPulledByAForce) {
  for (const double fraction : {0.5, 1.3}) {
    BodyDefinition def = floating_block(FrictionLaw::disc(0.3), 0.0, Eigen::Vector2d::Zero());
    def.dirichlet = {{"top", {2}, Eigen::Vector3d(0.0, 0.0, -1e-6)}};
    // P ≈ E·A/H·δ = 1.4e4 N for this block; the shear is `fraction` of 0.3·P.
    def.tractions = {{"top", Eigen::Vector3d(fraction * 0.3 * 1.4e4 / 0.01, 0.0, 0.0)}};
    ElasticBody body(def);
    EXPECT_EQ(body.num_floating_modes(), 3);
    const BodyState s = body.solve(def.initial_design);
    SCOPED_TRACE(s.contact->floating->brief_report());
    std::printf("fraction %.1f: %s\n", fraction, s.contact->floating->brief_report().c_str());
    if (fraction < 1.0) {
      ASSERT_EQ(s.summary.status, Status::kConverged);
      EXPECT_LE(relative_imbalance_off_contact(body, s), 1e-7);
      EXPECT_NEAR(-s.contact->resultants.tangential_force(0), fraction * 0.3 * 1.4e4, 1e-6 * 1.4e4);
    } else {
      EXPECT_NE(s.summary.status, Status::kConverged);
      EXPECT_NE(s.summary.message.find("exceeds the friction capacity"), std::string::npos)
          << s.summary.message;
    }
  }
}

TEST(FloatingBody, LoadsThatLiftTheBodyHaveNoEquilibrium) {
  ElasticBody body(floating_block(FrictionLaw::disc(0.3), -1e5, Eigen::Vector2d::Zero()));
  const BodyState s = body.solve(body.definition().initial_design);
  EXPECT_NE(s.summary.status, Status::kConverged);
  EXPECT_NE(s.summary.message.find("do not press the body"), std::string::npos)
      << s.summary.message;
}

TEST(FloatingBody, RigidModesAndFixingDofs) {
  Eigen::MatrixXd X(4, 3);
  X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  EXPECT_EQ(free_rigid_modes(X, {}).cols(), 6);
  EXPECT_EQ(free_rigid_modes(X, {2, 5, 8}).cols(),
            3);  // x3 of three nodes: x1, x2 and the x3-rotation stay free
  const Eigen::MatrixXd R = free_rigid_modes(X, {});
  const std::vector<int> fix = fixing_dofs(R, {}, {0}, 3);
  EXPECT_EQ(fix.size(), 6u);
  for (int d : fix) EXPECT_GE(d, 3);  // never on the excluded node 0
}

}  // namespace
}  // namespace frictopt::study
