// SPDX-License-Identifier: MIT
// The semismooth Newton method inside the direct engine (docs/contact.md, "Semismooth Newton"):
// the subgradient of a design evaluated on a Newton state equals the one on the fixed point's
// state (same index sets: the classification sees the same state), for an anisotropic polygon and
// an ellipse. The slip-heavy reproducer: semismooth_newton_slow_test.cpp.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "common/test_bodies.hpp"
#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/cost/cost_functional.hpp"
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
    const study::BodyDefinition base = frictopt::testing::dish_block_3d(law);
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

}  // namespace
}  // namespace frictopt::contact
