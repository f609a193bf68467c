// SPDX-License-Identifier: MIT
// Every state engine reports its state through one path (study::StateEngine::solve): the
// contact resultants, the node counts, the recorded law and the summary's method agree across
// the direct and the PETSc engine on a shipped 3D case, in the state and in summary.json.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "frictopt/io/case_file.hpp"
#include "frictopt/io/summary_json.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::petsc {
namespace {

// The engines' agreement in λ (tests/petsc/contact_newton_solver_test.cpp): 1e-6 relative.
constexpr double kAgreement = 1e-6;

TEST(EngineReport, TheSameResultantsAndCountsFromBothEnginesOnAShipped3DCase) {
  io::CaseDescription c = io::load_case("cases3d/punch-anisotropic/case.toml");
  c.body.resolution.cells = {8, 8, 4};  // 81 contact nodes: seconds per solve
  study::BodyDefinition petsc_definition = c.body;
  petsc_definition.engine.kind = study::StateEngine::kPetsc;
  study::ElasticBody direct_body(c.body);
  study::ElasticBody petsc_body(petsc_definition);
  EXPECT_EQ(direct_body.engine().name(), "direct");
  EXPECT_EQ(petsc_body.engine().name(), "petsc");
  const study::BodyState a = direct_body.solve(c.body.initial_design, "initial design");
  const study::BodyState b = petsc_body.solve(c.body.initial_design, "initial design");
  ASSERT_EQ(a.summary.status, Status::kConverged) << a.summary.message;
  ASSERT_EQ(b.summary.status, Status::kConverged) << b.summary.message;
  ASSERT_TRUE(a.contact && b.contact);

  const contact::ContactResultants& ra = a.contact->resultants;
  const contact::ContactResultants& rb = b.contact->resultants;
  ASSERT_GT(ra.normal_force, 0.0);
  EXPECT_NEAR(rb.normal_force, ra.normal_force, kAgreement * ra.normal_force);
  EXPECT_NEAR(rb.tangential_force_norm, ra.tangential_force_norm, kAgreement * ra.normal_force);
  EXPECT_GT(ra.contact_area, 0.0);
  EXPECT_NEAR(rb.contact_area, ra.contact_area, 1e-12 * ra.contact_area);
  EXPECT_EQ(rb.num_stick, ra.num_stick);
  EXPECT_EQ(rb.num_slip, ra.num_slip);
  EXPECT_EQ(rb.num_separated, ra.num_separated);
  EXPECT_EQ(ra.num_stick + ra.num_slip + ra.num_separated, a.contact->state.num_nodes());
  // Each state records the law it was solved with: the case's.
  ASSERT_TRUE(a.contact->law && b.contact->law);
  EXPECT_EQ(a.contact->law->describe(), c.body.contact->law.describe());
  EXPECT_EQ(b.contact->law->describe(), c.body.contact->law.describe());
  // The summary names the method that ran, with its last increment.
  EXPECT_EQ(a.contact->summary.method_used, contact::CoulombMethod::kFixedPoint);
  EXPECT_EQ(b.contact->summary.method_used, contact::CoulombMethod::kSemismoothNewton);
  EXPECT_TRUE(std::isfinite(b.contact->summary.last_relative_increment));

  // summary.json reads the same numbers from either engine.
  const io::JsonValue ja = io::solve_summary("punch-anisotropic", direct_body, a);
  const io::JsonValue jb = io::solve_summary("punch-anisotropic", petsc_body, b);
  const double pa = ja.at("contact").at("total_normal_force").as_number();
  const double pb = jb.at("contact").at("total_normal_force").as_number();
  EXPECT_EQ(pa, ra.normal_force);
  EXPECT_NEAR(pb, pa, kAgreement * pa);
  for (const char* key : {"num_stick", "num_slip", "num_separated"})
    EXPECT_EQ(jb.at("contact").at(key).as_integer(), ja.at("contact").at(key).as_integer()) << key;
  EXPECT_EQ(jb.at("contact").at("method_used").as_string(), "semismooth_newton");
}

}  // namespace
}  // namespace frictopt::petsc
