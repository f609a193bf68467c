// SPDX-License-Identifier: MIT
// The semismooth Newton method inside the direct engine (docs/contact.md, "Semismooth Newton"):
// the subgradient of a design evaluated on a Newton state equals the one on the fixed point's
// state (same index sets: the classification sees the same state), for an anisotropic polygon and
// an ellipse. The slip-heavy reproducer: semismooth_newton_slow_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>
#include <string>

#include "common/test_bodies.hpp"
#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/cost/cost_functional.hpp"
#include "frictopt/study/build_mesh.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::contact {
namespace {

study::BodyDefinition with_method(study::BodyDefinition b, CoulombMethod method) {
  b.contact->coulomb = study::ContactDefinition{}.coulomb;  // the default tolerances
  b.contact->coulomb.method = method;
  return b;
}

TEST(SemismoothNewtonState, SubgradientAfterANewtonStateIsTheFixedPointOnes) {
  for (const auto& [name, law] : {std::pair<std::string, FrictionLaw>{"anisotropic 4-gon", FrictionLaw::polygon({0.2, 0.4, 0.2, 0.4})},
                                  std::pair<std::string, FrictionLaw>{"ellipse", FrictionLaw::ellipse(0.2, 0.4)}}) {
    // The plate's first drag (of a decreasing few) that leaves stick and slip nodes.
    study::BodyDefinition base;
    for (const double drag : {2e-4, 1e-4, 5e-5, 2e-5, 1e-5}) {
      base = frictopt::testing::dish_block_3d(law, Eigen::Vector3d(drag, 0.5 * drag, -1.2e-3));
      study::ElasticBody probe(with_method(base, CoulombMethod::kFixedPoint));
      const study::BodyState s = probe.solve(base.initial_design, "probe");
      if (s.contact->resultants.num_stick > 0 && s.contact->resultants.num_slip > 0) break;
    }
    study::ElasticBody fp_body(with_method(base, CoulombMethod::kFixedPoint));
    study::ElasticBody newton_body(with_method(base, CoulombMethod::kSemismoothNewton));
    study::ShapeOracle fp(fp_body, cost::make_pressure_norm(6.0));
    study::ShapeOracle newton(newton_body, cost::make_pressure_norm(6.0));
    const Eigen::VectorXd alpha = base.initial_design;
    const study::Evaluation a = fp.evaluate_design(alpha);
    const study::Evaluation b = newton.evaluate_design(alpha);
    ASSERT_TRUE(a.ok) << a.message;
    ASSERT_TRUE(b.ok) << b.message;
    std::printf("%s: fixed point %s\n  Newton %s\n  %s\n", name.c_str(), a.contact.brief_report().c_str(),
                b.contact.brief_report().c_str(), b.index_sets.summary().c_str());
    EXPECT_EQ(a.contact.method_used, CoulombMethod::kFixedPoint);
    EXPECT_EQ(b.contact.method_used, CoulombMethod::kSemismoothNewton) << name;
    EXPECT_FALSE(b.contact.fallback) << name;
    EXPECT_GT(b.resultants.num_slip, 0) << name;
    EXPECT_GT(b.resultants.num_stick, 0) << name;
    EXPECT_GT(b.resultants.num_separated, 0) << name;
    EXPECT_EQ(a.index_sets.summary(), b.index_sets.summary()) << name;
    EXPECT_NEAR(b.value, a.value, 1e-8 * std::abs(a.value)) << name;
    ASSERT_EQ(a.subgradient.size(), b.subgradient.size());
    EXPECT_LE((b.subgradient - a.subgradient).norm(), 1e-6 * a.subgradient.norm()) << name;
  }
}


// The up-front estimate counts contact nodes (docs/scaling.md, "Contact nodes"): the dense M,
// 8·m², and from 3,000 contact unknowns the Newton LU, 4·m² more; a large surface gets a note
// before the solve, and the memory refusal names the contact nodes.
TEST(ContactCostEstimate, CountsContactNodes) {
  EXPECT_DOUBLE_EQ(study::estimated_contact_bytes(0), 0.0);
  EXPECT_DOUBLE_EQ(study::estimated_contact_bytes(1'000), 8e6);
  EXPECT_DOUBLE_EQ(study::estimated_contact_bytes(3'000), 12.0 * 9e6);
  EXPECT_DOUBLE_EQ(study::estimated_contact_bytes(20'000), 12.0 * 1.44e8);  // the dense bound: 12,000
  EXPECT_GT(study::estimated_contact_flops(3'267), 4.0 * 2.0 / 3.0 * 3'267.0 * 3'267.0 * 3'266.0);
  EXPECT_TRUE(study::contact_cost_note(3, 300).empty());
  const std::string note = study::contact_cost_note(3, 4'000);
  EXPECT_NE(note.find("4000 contact nodes (12000 contact unknowns)"), std::string::npos) << note;
  const study::BodyDefinition body = frictopt::testing::dish_block_3d(FrictionLaw::disc(0.3));
  const std::uint64_t limit = study::memory_limit();
  study::set_memory_limit(1000);
  try {
    (void)study::build_mesh(body);
    ADD_FAILURE() << "a 1000-byte limit must refuse the mesh";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("and 81 contact nodes"), std::string::npos) << e.what();
  }
  study::set_memory_limit(limit);
}

}  // namespace
}  // namespace frictopt::contact
