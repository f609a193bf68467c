// SPDX-License-Identifier: MIT
// The reproducer of the slow slip-heavy Coulomb state (docs/contact.md, "Semismooth Newton"): a
// 32 × 32 × 8 box with a flat bottom pressed and dragged so that most of its 3,267 contact
// unknowns slip; the automatic choice hands over to the semismooth Newton method, whose state
// agrees with the fixed point's (slow: both methods are run).
#include <gtest/gtest.h>

#include <cstdio>

#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::contact {
namespace {

// The slow slip-heavy state (docs/contact.md, "Semismooth Newton"): a rubber-like pad (ν = 0.49,
// which couples the normal and tangential responses strongly) 1 × 1 × 0.25 m on a 32 × 32 × 8 grid
// graded toward the contact surface, flat bottom (all 1,089 bottom nodes touch), top moved
// 1.2e-3 m down and 2e-4 m sideways, the anisotropic 4-gon (μ 0.4 and 0.2 along the diagonals,
// thesis remark 6.2.1): 1,039 of the 1,089 contact nodes slip, and the fixed point needs about
// 1,280 products with M, more than the m/10 = 327 of the automatic handover; Newton finishes and
// agrees with the fixed point.
TEST(SemismoothNewtonSlow, SlipHeavyBoxHandsOverToNewtonAndAgrees) {
  study::BodyDefinition b;
  b.shape = shape::BezierShape::surface(1.0, 1.0, 3, 3);
  b.height = 0.25;
  b.resolution = {{32, 32, 8}, 2.0};
  b.material = {7e10, 0.49, fem::PlaneModel::kPlaneStrain};
  b.dirichlet = {{"top", {}, Eigen::Vector3d(2e-4, 0.0, -1.2e-3)}};
  b.admissible.upper_bound = 5e-3;
  b.admissible.height = 0.25;
  b.initial_design = Eigen::VectorXd::Zero(9);
  study::ContactDefinition c;
  c.law = FrictionLaw::polygon({0.4, 0.2, 0.4, 0.2});
  b.contact = c;
  EXPECT_EQ(b.contact->coulomb.method, CoulombMethod::kAutomatic);  // the default
  study::ElasticBody automatic(b);
  const study::BodyState s = automatic.solve(b.initial_design, "automatic");
  ASSERT_TRUE(s.contact);
  const CoulombSolver::Summary& r = s.contact->summary;
  std::printf("automatic: %s\n  %s\n  factorization %.2f s, contact solve %.2f s\n", r.brief_report().c_str(),
              r.message.c_str(), s.summary.factorization_seconds, r.time_seconds);
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_GE(s.contact->state.z.size(), 3000);
  EXPECT_EQ(r.method_given, CoulombMethod::kAutomatic);
  EXPECT_EQ(r.method_used, CoulombMethod::kSemismoothNewton) << r.message;
  EXPECT_FALSE(r.fallback);
  EXPECT_GT(s.contact->resultants.num_slip, 4 * s.contact->resultants.num_stick) << "a slip-heavy state";

  b.contact->coulomb.method = CoulombMethod::kFixedPoint;
  study::ElasticBody fixed_point(b);
  const study::BodyState f = fixed_point.solve(b.initial_design, "fixed point");
  ASSERT_TRUE(f.contact && f.contact->summary.converged()) << f.contact->summary.message;
  std::printf("fixed point: %s\n", f.contact->summary.brief_report().c_str());
  const Eigen::VectorXd& z = s.contact->state.z;
  const Eigen::VectorXd& zf = f.contact->state.z;
  EXPECT_LE((z - zf).cwiseAbs().maxCoeff() / zf.cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_EQ(s.contact->resultants.num_slip, f.contact->resultants.num_slip);
  EXPECT_EQ(s.contact->resultants.num_stick, f.contact->resultants.num_stick);
  EXPECT_EQ(s.contact->resultants.num_separated, f.contact->resultants.num_separated);
}

}  // namespace
}  // namespace frictopt::contact
