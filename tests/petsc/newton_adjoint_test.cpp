// SPDX-License-Identifier: MIT
// The PETSc engine's adjoint (docs/petsc-engine.md, "Subgradient"): one
// transposed Krylov solve with the Newton Jacobian at the converged state gives the same ξ as
// the direct engine's adjoint (CHOLMOD, dual contact system; itself checked against central
// differences in tests/sensitivity) on the shipped 3D cases, for costs that exercise every
// term of ξ: ∇_z J (traction uniformity; the target pressure in ShippedCases/SubgradientAgrees),
// ∇_u J and ∇_α J (compliance), ∇_u J through u_t (total slip). Runs on 1 rank and under mpiexec -n 2 and -n 4 (ShippedCases/*).
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <ostream>
#include <string>

#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/petsc/contact_newton_solver.hpp"
#include "frictopt/petsc/petsc_session.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::petsc {
namespace {

// The tolerance for ξ between the engines.
constexpr double kSubgradientAgreement = 1e-5;

struct AdjointCase {
  std::string case_name;
  std::string cost;  // "compliance", "uniformity", "slip"
};

void PrintTo(const AdjointCase& c, std::ostream* out) { *out << c.case_name << " / " << c.cost; }

std::unique_ptr<cost::CostFunctional> make_test_cost(const std::string& kind) {
  if (kind == "compliance") return cost::make_compliance();
  if (kind == "uniformity") return cost::make_traction_uniformity();
  return cost::make_total_slip(1e-6);  // "slip": δ = 1 µm, below the punch's slip
}

class NewtonAdjoint : public ::testing::TestWithParam<AdjointCase> {};

TEST_P(NewtonAdjoint, GivesTheDirectEnginesSubgradient) {
  io::CaseDescription c = io::load_case("cases3d/" + GetParam().case_name + "/case.toml");
  c.body.resolution.cells = {8, 8, 4};  // 405 nodes, 81 contact nodes
  study::BodyDefinition petsc_definition = c.body;
  petsc_definition.engine.kind = study::StateEngine::kPetsc;
  study::ElasticBody direct_body(c.body);
  study::ElasticBody petsc_body(petsc_definition);
  study::ShapeOracle direct(direct_body, make_test_cost(GetParam().cost));
  study::ShapeOracle petsc(petsc_body, make_test_cost(GetParam().cost));
  const study::Evaluation& a = direct.evaluate_design(c.body.initial_design);
  const study::Evaluation& b = petsc.evaluate_design(c.body.initial_design);
  ASSERT_TRUE(a.ok) << a.message;
  ASSERT_TRUE(b.ok) << b.message;
  ASSERT_GT(a.subgradient.norm(), 0.0);
  if (PetscSession::rank() == 0)
    std::printf("   ξ relative difference %.2e; %s\n", (b.subgradient - a.subgradient).norm() / a.subgradient.norm(),
              b.adjoint.message.c_str());
  EXPECT_LE((b.subgradient - a.subgradient).norm(), kSubgradientAgreement * a.subgradient.norm())
      << "direct: " << a.subgradient.transpose() << "\npetsc:  " << b.subgradient.transpose() << "\n"
      << b.adjoint.brief_report();
  // The engine's own solve: converged, to its tolerance, and reported as such.
  EXPECT_EQ(b.adjoint.status, Status::kConverged) << b.adjoint.brief_report();
  EXPECT_LE(b.adjoint.relative_residual, 1e-9) << b.adjoint.brief_report();
  EXPECT_NE(b.adjoint.message.find("one transposed solve"), std::string::npos) << b.adjoint.message;
  EXPECT_EQ(a.index_sets.summary(), b.index_sets.summary());
}

INSTANTIATE_TEST_SUITE_P(
    ShippedCases, NewtonAdjoint,
    // The cases' own target-pressure costs are ShippedCases/SubgradientAgrees
    // (contact_newton_solver_test.cpp), which goes through the same path.
    ::testing::Values(AdjointCase{"punch", "slip"}, AdjointCase{"punch-anisotropic", "uniformity"},
                      AdjointCase{"punch-anisotropic", "compliance"}, AdjointCase{"punch-elliptic", "slip"}),
    [](const ::testing::TestParamInfo<AdjointCase>& param_info) {
      std::string name = param_info.param.case_name + "_" + param_info.param.cost;
      for (char& ch : name)
        if (ch == '-') ch = '_';
      return name;
    });

// Bad input: partials of the wrong size are refused with the sizes named, not read past.
TEST(ContactNewtonSolver, SubgradientRefusesPartialsOfTheWrongSize) {
  io::CaseDescription c = io::load_case("cases3d/punch/case.toml");
  c.body.resolution.cells = {8, 8, 4};
  study::ElasticBody body(c.body);
  ContactNewtonSolver solver(body.elasticity(), *body.contact_boundary(), c.body.contact->law, {});
  const Eigen::MatrixXd X = body.mesh().positions(c.body.initial_design);
  Eigen::VectorXd u;
  contact::ContactState state;
  ASSERT_TRUE(solver.solve(X, body.contact_boundary()->gaps(X), u, state).converged());
  const Eigen::MatrixXd gap_matrix = body.contact_boundary()->gap_jacobian(body.mesh());
  const Eigen::VectorXd too_short = Eigen::VectorXd::Zero(u.size() - 1);
  EXPECT_THROW((void)solver.subgradient(X, u, Eigen::VectorXd(), too_short, Eigen::VectorXd(), gap_matrix), InvalidInput);
}

}  // namespace
}  // namespace frictopt::petsc
