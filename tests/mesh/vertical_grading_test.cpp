// SPDX-License-Identifier: MIT
// The vertical grading "contact" of structured grids (docs/contact-validation.md §1c): equal layers
// down to mesh.fine_depth, geometric growth above; the morph X_ref + V α on them, and the refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/finite_difference.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/mesh/graded_coordinates.hpp"
#include "frictopt/mesh/structured_mesh.hpp"

namespace frictopt::mesh {
namespace {

std::string message_of(const auto& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "no exception";
}

// Checks the layer heights: 0 and height exactly, fine_depth a layer line exactly, equal layers
// below it, above it layers no thinner than the fine ones growing by a ratio in [1, growth].
// Returns the fine layer thickness.
double expect_contact_layers(const std::vector<double>& z, double height, double fine_depth, double growth) {
  EXPECT_EQ(z.front(), 0.0);
  EXPECT_EQ(z.back(), height);
  const auto at_depth = std::find(z.begin(), z.end(), fine_depth);
  EXPECT_NE(at_depth, z.end()) << "fine_depth = " << fine_depth << " is not a layer line";
  if (at_depth == z.end()) return 0.0;
  const double t = fine_depth / static_cast<double>(at_depth - z.begin());
  for (std::size_t k = 0; k + 1 < z.size(); ++k) {
    const double thickness = z[k + 1] - z[k];
    if (z[k + 1] <= fine_depth)
      EXPECT_NEAR(thickness, t, 1e-12 * height) << "fine layer " << k;
    else
      EXPECT_GE(thickness, t * (1 - 1e-9)) << "upper layer " << k;
    if (k + 2 < z.size()) {
      const double next = z[k + 2] - z[k + 1];
      EXPECT_GE(next, thickness * (1 - 1e-9)) << "layers thin out upward at " << k;
      EXPECT_LE(next / thickness, growth * (1 + 1e-9)) << "layers " << k << ", " << k + 1;
    }
  }
  return t;
}

TEST(ContactLayerCoordinates, EqualLayersDownToFineDepthThenGeometricGrowth) {
  struct Case {
    double height, depth, growth;
    int layers;
  };
  for (const Case& c : {Case{1.0, 0.16, 1.3, 16}, Case{1.0, 0.2, 1.2, 18}, Case{2.0, 0.5, 1.5, 10},
                        Case{0.5, 0.05, 2.0, 9}, Case{1.0, 0.16, 1.25, 40}}) {
    SCOPED_TRACE(std::to_string(c.layers) + " layers, fine_depth " + std::to_string(c.depth) + ", growth " +
                 std::to_string(c.growth));
    const std::vector<double> z = contact_layer_coordinates(c.height, c.layers, c.depth, c.growth);
    ASSERT_EQ(z.size(), static_cast<std::size_t>(c.layers) + 1);
    const double t = expect_contact_layers(z, c.height, c.depth, c.growth);
    EXPECT_LT(t, c.height / c.layers);  // finer than uniform layers at the contact surface
  }
}

TEST(ContactLayerCoordinates, MoreLayersMakeTheFineLayersThinner) {
  double previous = INFINITY;
  for (int layers : {12, 16, 20, 28}) {
    const std::vector<double> z = contact_layer_coordinates(1.0, layers, 0.16, 1.3);
    const double t = z[1] - z[0];
    EXPECT_LE(t, previous) << layers << " layers";
    previous = t;
  }
  // 16 layers at growth 1.3 keep 7 equal layers of 0.16/7 m: the finest the count allows
  // (8 fine layers would leave 8 layers that cannot reach the top growing by <= 1.3).
  const std::vector<double> z = contact_layer_coordinates(1.0, 16, 0.16, 1.3);
  EXPECT_EQ(z[7], 0.16);
  EXPECT_NEAR(z[1], 0.16 / 7, 1e-15);
}

TEST(ContactLayerCoordinates, RefusesNamingTheField) {
  EXPECT_NE(message_of([] { contact_layer_coordinates(1.0, 10, 1.0, 1.2); }).find("mesh.fine_depth = 1"),
            std::string::npos);
  EXPECT_NE(message_of([] { contact_layer_coordinates(1.0, 10, 0.0, 1.2); }).find("mesh.fine_depth"),
            std::string::npos);
  EXPECT_NE(message_of([] { contact_layer_coordinates(1.0, 10, 0.2, 1.0); }).find("mesh.vertical_growth = 1"),
            std::string::npos);
  EXPECT_NE(message_of([] { contact_layer_coordinates(1.0, 10, 0.2, 2.5); }).find("mesh.vertical_growth = 2.5"),
            std::string::npos);
  // 3 layers cannot grow from at least 0.02 m to fill 0.98 m by a ratio <= 1.1.
  EXPECT_NE(message_of([] { contact_layer_coordinates(1.0, 3, 0.02, 1.1); }).find("mesh.cells[vertical] = 3"),
            std::string::npos);
}

GridResolution contact_resolution(std::array<int, 3> cells, double depth, double growth) {
  GridResolution resolution;
  resolution.cells = cells;
  resolution.vertical_grading = VerticalGrading::kContact;
  resolution.fine_depth = depth;
  resolution.vertical_growth = growth;
  return resolution;
}

TEST(ContactVerticalGrading, LayersSitAtTheContactLayerCoordinates) {
  const auto surface = shape::BezierShape::surface(1.0, 1.0, 3, 3);
  GridResolution resolution = contact_resolution({12, 14, 14}, 0.3, 1.3);
  resolution.growth = 1.2;  // combined with in-plane grading
  const StructuredMesh grid(surface, 1.5, resolution);
  const std::vector<double> z = contact_layer_coordinates(1.5, 14, 0.3, 1.3);
  const Eigen::MatrixXd& X = grid.mesh().reference_positions();
  for (int k = 0; k <= 14; ++k) {
    EXPECT_NEAR(grid.layer_parameter(k) * 1.5, z[static_cast<std::size_t>(k)], 1e-15) << "layer " << k;
    EXPECT_NEAR(X(grid.node(3, 2, k), 2), z[static_cast<std::size_t>(k)], 1e-15) << "layer " << k;
  }
  EXPECT_EQ(grid.layer_parameter(14), 1.0);  // the top exactly: it does not move
}

// The morph stays X(α) = X_ref + V α with a constant V: V against central differences of the
// positions, affine in α, and the bottom on the Bézier surface, in 2D and 3D.
TEST(ContactVerticalGrading, DesignJacobianIsConstantAndMatchesCentralDifferences) {
  for (int dim : {2, 3}) {
    SCOPED_TRACE(std::to_string(dim) + "D");
    const auto shape = dim == 2 ? shape::BezierShape::curve(1.0, 5) : shape::BezierShape::surface(1.0, 1.0, 3, 3);
    GridResolution resolution = contact_resolution({12, 10, 12}, 0.25, 1.4);
    resolution.growth = 1.3;
    const StructuredMesh grid(shape, 1.0, resolution);
    Eigen::VectorXd alpha(shape.num_controls());
    for (int k = 0; k < alpha.size(); ++k) alpha(k) = 0.2 + 0.1 * std::sin(1.7 * k + 0.3);
    const auto positions = [&](const Eigen::VectorXd& a) {
      const Eigen::MatrixXd X = grid.mesh().positions(a);
      Eigen::VectorXd flat(X.size());
      for (int n = 0; n < X.rows(); ++n) flat.segment(n * dim, dim) = X.row(n).transpose();
      return flat;
    };
    const Eigen::MatrixXd fd =
        frictopt::testing::central_jacobian(positions, alpha, frictopt::testing::central_step(alpha));
    const Eigen::MatrixXd V = Eigen::MatrixXd(grid.mesh().design_jacobian());
    EXPECT_LE((fd - V).norm(), 1e-9 * V.norm());
    const Eigen::VectorXd x0 = positions(Eigen::VectorXd::Zero(alpha.size()));
    EXPECT_LE((positions(alpha) - x0 - V * alpha).norm(), 1e-13 * x0.norm());
    const Eigen::MatrixXd X = grid.mesh().positions(alpha);
    for (int node : grid.face(Face::kBottom).nodes)
      EXPECT_NEAR(X(node, dim - 1), shape.height(alpha, X.row(node).head(dim - 1).transpose()), 1e-15);
    EXPECT_GT(grid.mesh().min_scaled_jacobian(X), 0.0);
  }
}

TEST(ContactVerticalGrading, RefusesAPowerLawGradingAndLayersThatCannotFit) {
  const auto curve = shape::BezierShape::curve(1.0, 3);
  GridResolution resolution = contact_resolution({8, 0, 12}, 0.2, 1.3);
  resolution.grading = 2.0;
  EXPECT_NE(message_of([&] { StructuredMesh(curve, 1.0, resolution); }).find("mesh.grading = 2"), std::string::npos);
  resolution.grading = 1.0;
  resolution.fine_depth = 1.5;
  EXPECT_NE(message_of([&] { StructuredMesh(curve, 1.0, resolution); }).find("mesh.fine_depth = 1.5"),
            std::string::npos);
}

}  // namespace
}  // namespace frictopt::mesh
