// SPDX-License-Identifier: MIT
// ElasticBody on meshes at the edge of what the pipeline handles.
#include "frictopt/study/elastic_body.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <array>

namespace frictopt::study {
namespace {

// One cell layer under a top face that is fixed completely (a rigid plate pressed down): the
// only free DOFs are those of the contact nodes, so the factorization's leading block (the
// non-contact DOFs) is empty. This once crashed with SIGSEGV in Release
// (`cells = [4, 4, 1]`, 2D `[29, 1]`), CHOLMOD's analysis of the empty block returning NULL.
BodyDefinition one_layer_body(int dim) {
  BodyDefinition b;
  b.height = 0.5;
  if (dim == 2) {
    b.shape = shape::BezierShape::curve(1.0, 4);
    b.resolution = {{29, 0, 1}, 1.0};
    b.dirichlet = {{"top", {}, Eigen::Vector2d(1e-4, -1.2e-3)}};
    b.contact = ContactDefinition{};
    b.contact->law = contact::FrictionLaw::interval(0.3, 0.3);
  } else {
    b.shape = shape::BezierShape::surface(1.0, 1.0, 2, 2);
    b.resolution = {{4, 4, 1}, 1.0};
    b.dirichlet = {{"top", {}, Eigen::Vector3d(1e-4, 0.0, -1.2e-3)}};
    b.contact = ContactDefinition{};
    b.contact->law = contact::FrictionLaw::disc(0.3);
  }
  b.material = {7e10, 0.33, fem::PlaneModel::kPlaneStrain};
  b.admissible.upper_bound = 5e-3;
  b.admissible.height = b.height;
  b.initial_design = Eigen::VectorXd::Constant(b.shape.num_controls(), 1e-3);
  b.admissible.volume = b.height - 1e-3;  // unit width (and depth): mean gap 1 mm
  return b;
}

class OneCellLayer : public ::testing::TestWithParam<int> {};

TEST_P(OneCellLayer, SolvesWhenOnlyTheContactDofsAreFree) {
  const int dim = GetParam();
  ElasticBody body(one_layer_body(dim));
  const contact::ContactBoundary& boundary = *body.contact_boundary();
  ASSERT_EQ(boundary.num_unknowns(), body.elasticity().dofs().num_free());  // the leading block is empty
  const BodyState state = body.solve(body.definition().initial_design, "initial design");
  ASSERT_EQ(state.summary.status, Status::kConverged) << state.summary.message;
  ASSERT_TRUE(state.contact.has_value());
  // The plate moves down by 1.2 mm onto gaps of 1 mm: the bottom is pressed into contact.
  double total_normal_force = 0.0;
  for (Eigen::Index i = 0; i < boundary.num_nodes(); ++i) total_normal_force += state.contact->state.lambda(i);
  EXPECT_GT(total_normal_force, 0.0);
  // Equilibrium of the factorized system to round-off (backward-stable Cholesky: ~1e3·eps).
  EXPECT_LE(state.summary.relative_residual, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Dims, OneCellLayer, ::testing::Values(2, 3),
                         [](const ::testing::TestParamInfo<int>& param_info) { return "Dim" + std::to_string(param_info.param); });

}  // namespace
}  // namespace frictopt::study
