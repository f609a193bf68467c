// SPDX-License-Identifier: MIT
// The orientation φ of a turned friction law as a parameter (docs/theory/friction-frame.md §2): the
// forward derivative of the contact state in φ (friction_parameter_rows with orientation_parameter,
// then contact_state_derivative) against central differences of fresh state solves, for every
// 3D law at a point whose index sets are strict; and the parameter bookkeeping.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "common/test_bodies.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/sensitivity/friction_parameters.hpp"
#include "frictopt/sensitivity/index_sets.hpp"
#include "frictopt/sensitivity/parameter_sensitivity.hpp"
#include "frictopt/sensitivity/piece.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::sensitivity {
namespace {

// A 3D block pressed and dragged by a rigid plate on its top (prescribed displacement), with a
// dish-shaped bottom: stick, slip and separated nodes all occur.
study::BodyDefinition block_3d(const contact::FrictionLaw& law) {
  return frictopt::testing::dish_block_3d(law, Eigen::Vector3d(2e-4, 1e-4, -1.2e-3));
}

Eigen::VectorXd contact_forces(const contact::FrictionLaw& law) {
  study::ElasticBody body(block_3d(law));
  const study::BodyState s = body.solve(body.definition().initial_design);
  EXPECT_TRUE(s.contact && s.contact->summary.converged());
  return s.contact->state.z;
}

struct OrientationCase {
  std::string name;
  contact::FrictionLaw law;  // unturned; the test turns it by φ₀
};

class OrientationDerivative : public ::testing::TestWithParam<OrientationCase> {};

// δz/δφ from the piece's linear system against (z(φ₀+ε) − z(φ₀−ε))/2ε. The piece is fixed for
// |ε| small where the index sets are strict, so the difference quotient is exact up to O(ε²)
// and the state tolerance (1e-14 relative): ε = 1e-6 gives ~1e-9 relative; 1e-6 is the bound.
TEST_P(OrientationDerivative, MatchesCentralDifferencesOfTheState) {
  const OrientationCase& c = GetParam();
  const double phi0 = 0.4;
  const contact::FrictionLaw law = c.law.rotated(phi0);
  study::ElasticBody body(block_3d(law));
  const study::BodyState s = body.solve(body.definition().initial_design);
  ASSERT_TRUE(s.contact && s.contact->summary.converged());
  ASSERT_TRUE(s.contact->delassus_matrix) << "the test needs the dense Delassus matrix";
  const contact::ContactState& state = s.contact->state;
  const IndexSets sets = classify(state, law);
  ASSERT_EQ(sets.num_weak_nodes(), 0) << sets.summary();
  const Piece piece = default_piece(sets);
  const PieceLinearization lin = linearize_piece(piece, law, state);
  const FrictionParameters orientation = orientation_parameter(law);
  const Eigen::MatrixXd rows = friction_parameter_rows(piece, law, state, orientation);
  const ContactStateDerivative d = contact_state_derivative(lin, *s.contact->delassus_matrix, rows, Eigen::MatrixXd());
  ASSERT_EQ(d.status, Status::kConverged) << d.message;

  const double eps = 1e-6;
  const Eigen::VectorXd fd = (contact_forces(c.law.rotated(phi0 + eps)) - contact_forces(c.law.rotated(phi0 - eps))) / (2 * eps);
  const double scale = state.z.norm();
  const double error = (d.forces.col(0) - fd).norm() / std::max(fd.norm(), 1e-3 * scale);
  std::printf("%s: |dz/dphi| forward %.4e, FD %.4e, relative error %.2e (%s)\n", c.name.c_str(),
              d.forces.col(0).norm(), fd.norm(), error, sets.summary().c_str());
  EXPECT_LE(error, 1e-6);
  if (c.law.kind() == contact::FrictionLawKind::kDisc) {
    // A disc does not change when turned: ∂w/∂φ = J w − (∂w/∂u) J u = 0 up to rounding (the
    // two terms are each of size λμ ~ |z| and cancel to ~1e-16 relative).
    EXPECT_LE(rows.norm(), 1e-14 * scale);
    EXPECT_LE(fd.norm(), 1e-6 * scale);
  } else {
    EXPECT_GT(fd.norm(), 1e-2 * scale) << "the orientation should move the state";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Laws, OrientationDerivative,
    ::testing::Values(OrientationCase{"RegularPolygon", contact::FrictionLaw::regular_polygon(0.3, 6)},
                      OrientationCase{"AnisotropicPolygon", contact::FrictionLaw::polygon({0.2, 0.45, 0.25, 0.4})},
                      OrientationCase{"EllipsePolygon", contact::FrictionLaw::ellipse_polygon(0.2, 0.4, 16)},
                      OrientationCase{"Disc", contact::FrictionLaw::disc(0.3)},
                      OrientationCase{"Ellipse", contact::FrictionLaw::ellipse(0.2, 0.4)}),
    [](const auto& test_case) { return test_case.param.name; });

TEST(OrientationParameter, IsListedOnlyWhenAskedAndRoundTrips) {
  const contact::FrictionLaw law = contact::FrictionLaw::polygon({0.2, 0.45, 0.25, 0.4}).rotated(0.3);
  const FrictionParameters plain = friction_parameters(law);
  EXPECT_EQ(plain.values.size(), 4);
  const FrictionParameters with = friction_parameters(law, {.orientation = true});
  ASSERT_EQ(with.values.size(), 5);
  EXPECT_EQ(with.names.back(), "orientation");
  EXPECT_DOUBLE_EQ(with.values(4), 0.3);
  // The coefficients of a turned polygon are its own (|w_j|), not the turned coordinates.
  EXPECT_LE((plain.values - Eigen::Vector4d(0.2, 0.45, 0.25, 0.4)).norm(), 1e-15);
  const FrictionParameters alone = orientation_parameter(law);
  ASSERT_EQ(alone.values.size(), 1);
  for (std::size_t j = 0; j < 4; ++j) {
    const Eigen::Vector2d w = law.vertices()[j];
    EXPECT_LE((alone.vertex_derivatives[0][j] - Eigen::Vector2d(-w.y(), w.x())).norm(), 1e-15);
    EXPECT_EQ(alone.vertex_derivatives[0][j], with.vertex_derivatives[4][j]);
  }
  Eigen::VectorXd values = with.values;
  values(4) = 1.0;
  const contact::FrictionLaw back = with_friction_parameters(law, values, {.orientation = true});
  EXPECT_DOUBLE_EQ(back.orientation(), 1.0);
  EXPECT_LE((back.vertices()[0] - contact::FrictionLaw::polygon({0.2, 0.45, 0.25, 0.4}).rotated(1.0).vertices()[0]).norm(),
            1e-15);
  // Without the orientation among the values the law keeps its angle.
  EXPECT_DOUBLE_EQ(with_friction_parameters(law, plain.values).orientation(), 0.3);
  const contact::FrictionLaw ellipse = contact::FrictionLaw::ellipse(0.2, 0.4).rotated(-0.5);
  const FrictionParameters e = friction_parameters(ellipse, {.orientation = true});
  EXPECT_EQ(e.semi_axis_derivatives.size(), 3u);
  EXPECT_EQ(e.orientation_derivatives, (std::vector<double>{0.0, 0.0, 1.0}));
  EXPECT_EQ(e.values, Eigen::Vector3d(0.2, 0.4, -0.5));
}

TEST(OrientationParameter, IsRefusedForA2DLaw) {
  try {
    (void)orientation_parameter(contact::FrictionLaw::interval(0.2, 0.3));
    ADD_FAILURE() << "a 2D law got an orientation parameter";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("no orientation parameter"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)friction_parameters(contact::FrictionLaw::interval(0.2, 0.3), {.orientation = true}), InvalidInput);
}

}  // namespace
}  // namespace frictopt::sensitivity
