// SPDX-License-Identifier: MIT
#include "frictopt/mesh/structured_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>
#include <random>

#include "common/finite_difference.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::mesh {
namespace {

using frictopt::testing::kSeed;

Eigen::VectorXd wavy_design(int d, double base, double amplitude) {
  Eigen::VectorXd alpha(d);
  for (int k = 0; k < d; ++k) alpha(k) = base + amplitude * std::sin(1.7 * k + 0.3);
  return alpha;
}

// Exact volume from the linear formula: base·C4 − ∫G_α = base·C4 − wᵀα (docs/theory/problem.md §2).
double linear_volume(const shape::BezierShape& s, double height, const Eigen::VectorXd& alpha) {
  return s.base_measure() * height - s.integral_weights().dot(alpha);
}

TEST(StructuredMesh, VolumeConvergesToLinearFormulaAtSecondOrder2D) {
  const auto curve = shape::BezierShape::curve(2.0, 15);
  const Eigen::VectorXd alpha = wavy_design(15, 0.3, 0.2);
  const double exact = linear_volume(curve, 1.0, alpha);
  std::vector<double> errors;
  for (int n : {8, 16, 32, 64}) {
    StructuredMesh mesh(curve, 1.0, {{n, 0, 4}, 1.0});
    errors.push_back(std::abs(mesh.mesh().volume(mesh.mesh().positions(alpha)) - exact));
  }
  for (std::size_t i = 0; i + 1 < errors.size(); ++i) {
    const double rate = std::log2(errors[i] / errors[i + 1]);
    // The bottom is interpolated piecewise linearly: the trapezoid rule's O(h²).
    EXPECT_NEAR(rate, 2.0, 0.15) << "refinement " << i << " errors " << errors[i] << " " << errors[i + 1];
    std::printf("2D volume: error %.3e -> %.3e, observed rate %.3f\n", errors[i], errors[i + 1], rate);
  }
}

TEST(StructuredMesh, VolumeConvergesToLinearFormulaAtSecondOrder3D) {
  const auto surface = shape::BezierShape::surface(1.0, 0.8, 4, 3);
  const Eigen::VectorXd alpha = wavy_design(12, 0.25, 0.15);
  const double exact = linear_volume(surface, 1.0, alpha);
  std::vector<double> errors;
  for (int n : {4, 8, 16}) {
    StructuredMesh mesh(surface, 1.0, {{n, n, 2}, 1.0});
    errors.push_back(std::abs(mesh.mesh().volume(mesh.mesh().positions(alpha)) - exact));
  }
  for (std::size_t i = 0; i + 1 < errors.size(); ++i) {
    const double rate = std::log2(errors[i] / errors[i + 1]);
    EXPECT_NEAR(rate, 2.0, 0.2);
    std::printf("3D volume: error %.3e -> %.3e, observed rate %.3f\n", errors[i], errors[i + 1], rate);
  }
}

TEST(StructuredMesh, DesignJacobianMatchesCentralDifferences) {
  const auto surface = shape::BezierShape::surface(1.0, 1.0, 3, 3);
  StructuredMesh mesh(surface, 1.0, {{3, 4, 3}, 2.0});
  std::mt19937_64 rng{kSeed};
  const Eigen::VectorXd alpha = wavy_design(9, 0.2, 0.1);
  const auto positions = [&](const Eigen::VectorXd& a) {
    const Eigen::MatrixXd X = mesh.mesh().positions(a);
    Eigen::VectorXd flat(X.size());
    for (int n = 0; n < X.rows(); ++n) flat.segment(n * 3, 3) = X.row(n).transpose();
    return flat;
  };
  const Eigen::MatrixXd fd =
      frictopt::testing::central_jacobian(positions, alpha, frictopt::testing::central_step(alpha));
  const Eigen::MatrixXd V = Eigen::MatrixXd(mesh.mesh().design_jacobian());
  // X is affine in α: the central difference is exact up to round-off (~eps/h·|X|).
  EXPECT_LE((fd - V).norm(), 1e-9 * V.norm());
}

TEST(StructuredMesh, BottomFollowsTheBezierSurfaceAndTopStaysFlat) {
  const auto curve = shape::BezierShape::curve(2.0, 5);
  StructuredMesh mesh(curve, 1.0, {{10, 0, 3}, 1.5});
  const Eigen::VectorXd alpha = wavy_design(5, 0.3, 0.1);
  const Eigen::MatrixXd X = mesh.mesh().positions(alpha);
  for (int node : mesh.face(Face::kBottom).nodes)
    EXPECT_NEAR(X(node, 1), curve.height(alpha, X.row(node).head(1).transpose()), 1e-15);
  for (int node : mesh.face(Face::kTop).nodes) EXPECT_NEAR(X(node, 1), 1.0, 1e-15);
}

TEST(StructuredMesh, FacesHaveTheExpectedSizes) {
  const auto surface = shape::BezierShape::surface(1.0, 1.0, 2, 2);
  StructuredMesh mesh(surface, 1.0, {{4, 3, 2}, 1.0});
  EXPECT_EQ(mesh.num_nodes(), 5 * 4 * 3);
  EXPECT_EQ(mesh.num_elements(), 4 * 3 * 2);
  EXPECT_EQ(mesh.face(Face::kLeft).nodes.size(), 4u * 3u);
  EXPECT_EQ(mesh.face(Face::kFront).nodes.size(), 5u * 3u);
  EXPECT_EQ(mesh.face(Face::kBottom).nodes.size(), 5u * 4u);
  EXPECT_EQ(mesh.face(Face::kTop).facets.rows(), 12);
  EXPECT_EQ(mesh.face(Face::kRight).facets.rows(), 6);
  const auto curve = shape::BezierShape::curve(1.0, 3);
  StructuredMesh mesh2(curve, 1.0, {{4, 0, 2}, 1.0});
  EXPECT_THROW((void)mesh2.face(Face::kFront), InvalidInput);
}

TEST(StructuredMesh, InvertedElementIsReportedWithElementAndDesign) {
  const auto curve = shape::BezierShape::curve(1.0, 3);
  StructuredMesh mesh(curve, 1.0, {{4, 0, 2}, 1.0});
  Eigen::VectorXd alpha(3);
  alpha << 0.1, 3.0, 0.1;  // peak height 0.05 + 1.5 > 1: the bottom rises above the top
  try {
    mesh.mesh().check_quality(mesh.mesh().positions(alpha), "design 12");
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("element"), std::string::npos) << what;
    EXPECT_NE(what.find("inverted"), std::string::npos) << what;
    EXPECT_NE(what.find("design 12"), std::string::npos) << what;
    EXPECT_NE(what.find("(column 0, layer 0)"), std::string::npos) << what;  // the grid's own location
  }
  alpha << 0.1, 0.5, 0.1;
  EXPECT_NO_THROW(mesh.mesh().check_quality(mesh.mesh().positions(alpha), "design 13"));
}

TEST(StructuredMesh, RejectsBadResolution) {
  const auto curve = shape::BezierShape::curve(1.0, 3);
  EXPECT_THROW(StructuredMesh(curve, 1.0, {{0, 0, 2}, 1.0}), InvalidInput);
  EXPECT_THROW(StructuredMesh(curve, 1.0, {{2, 0, 2}, 0.5}), InvalidInput);
  EXPECT_THROW((void)parse_face("bottomm"), InvalidInput);
}

TEST(StructuredMesh, FacesAreTheNamedBoundarySetsOfItsMesh) {
  const auto surface = shape::BezierShape::surface(1.0, 1.0, 2, 2);
  const StructuredMesh grid(surface, 1.0, {{2, 2, 2}, 1.0});
  const Mesh& mesh = grid.mesh();
  EXPECT_EQ(mesh.boundary_names(), (std::vector<std::string>{"back", "bottom", "front", "left", "right", "top"}));
  EXPECT_EQ(mesh.element_kind(), ElementKind::kHex8);
  EXPECT_EQ(mesh.vtk_cell_type(), 12);
  // The bottom's nodes are layer 0 in column order, the grid's (i1, i2, 0).
  const std::vector<int>& bottom = mesh.boundary("bottom").nodes;
  ASSERT_EQ(bottom.size(), 9u);
  EXPECT_EQ(bottom[4], grid.node(1, 1, 0));
  const StructuredMesh grid2d(shape::BezierShape::curve(1.0, 3), 1.0, {{3, 0, 2}, 1.0});
  EXPECT_EQ(grid2d.mesh().boundary_names(), (std::vector<std::string>{"bottom", "left", "right", "top"}));
  EXPECT_EQ(grid2d.mesh().element_kind(), ElementKind::kQuad4);
  try {
    (void)grid2d.mesh().boundary("front");
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'front'"), std::string::npos) << what;
    EXPECT_NE(what.find("bottom, left, right, top"), std::string::npos) << what;
  }
}

// The column and node counts overflowed 32-bit int (UBSan) for large
// resolutions. The counts are 64-bit and computed without allocating anything.
TEST(StructuredMesh, CountsOfAHugeGridDoNotOverflow) {
  const StructuredGridSizes sizes = structured_grid_sizes(3, {{100000, 100000, 100000}, 1.0});
  const std::int64_t side = 100001;
  EXPECT_EQ(sizes.columns, side * side);
  EXPECT_EQ(sizes.nodes, side * side * side);
  EXPECT_EQ(sizes.elements, std::int64_t{100000} * 100000 * 100000);
  EXPECT_EQ(sizes.dofs, 3 * side * side * side);
  const StructuredGridSizes flat = structured_grid_sizes(2, {{100000, 7, 100000}, 1.0});  // n2 ignored in 2D
  EXPECT_EQ(flat.columns, side);
  EXPECT_EQ(flat.nodes, side * side);
  EXPECT_EQ(flat.elements, std::int64_t{100000} * 100000);
}

TEST(StructuredMesh, RefusesAGridWhoseIndicesDoNotFitBeforeAllocating) {
  // 50,001² nodes × 2 = 5.0e9 unknowns > 2^31 − 1: refused with the counts, before any allocation.
  try {
    const StructuredMesh grid(shape::BezierShape::curve(1.0, 3), 1.0, {{50000, 0, 50000}, 1.0});
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("mesh.cells = [50000, 50000]"), std::string::npos) << what;
    EXPECT_NE(what.find("5000200002 unknowns"), std::string::npos) << what;
  }
}


// [mesh] element = "tet4"/"tri3": the grid's cells split into simplices on the same nodes. The split
// must be conforming (every interior face shared by exactly two simplices), its exterior faces must be
// exactly the named boundary sets' facets, every simplex positively oriented, and the volume the Q1
// grid's (exact for a flat design: the box; the bilinear faces of a morphed hexahedron are not
// planar, so a curved design's volumes differ at second order).
TEST(StructuredMesh, SplitIntoSimplicesIsConformingAndKeepsNodesFacesAndVolume) {
  for (int dim : {2, 3}) {
    SCOPED_TRACE(std::to_string(dim) + "D");
    const auto shape = dim == 2 ? shape::BezierShape::curve(1.0, 3) : shape::BezierShape::surface(1.0, 0.8, 3, 2);
    GridResolution q1{{5, 4, 3}, 1.3};
    GridResolution p1 = q1;
    p1.element_family = ElementFamily::kSimplex;
    const StructuredMesh hexes(shape, 0.6, q1), simplices(shape, 0.6, p1);
    const Mesh& mesh = simplices.mesh();
    EXPECT_EQ(mesh.element_kind(), dim == 2 ? ElementKind::kTri3 : ElementKind::kTet4);
    EXPECT_EQ(mesh.num_elements(), hexes.mesh().num_elements() * (dim == 2 ? 2 : 6));
    EXPECT_EQ(mesh.reference_positions(), hexes.mesh().reference_positions());
    EXPECT_EQ((mesh.design_jacobian() - hexes.mesh().design_jacobian()).norm(), 0.0);
    const Eigen::VectorXd flat = Eigen::VectorXd::Zero(shape.num_controls());
    EXPECT_NEAR(mesh.volume(mesh.positions(flat)), hexes.mesh().volume(hexes.mesh().positions(flat)), 1e-14);
    Eigen::VectorXd curved = Eigen::VectorXd::LinSpaced(shape.num_controls(), 0.0, 0.2);
    const double v_p1 = mesh.volume(mesh.positions(curved)), v_q1 = hexes.mesh().volume(hexes.mesh().positions(curved));
    EXPECT_NEAR(v_p1, v_q1, 1e-2 * v_q1);
    EXPECT_GT(mesh.min_scaled_jacobian(mesh.positions(curved)), 0.1);
    // Conformity and boundary facets: each facet key (sorted nodes) of the cells counted.
    const std::vector<std::vector<int>> local =
        dim == 2 ? std::vector<std::vector<int>>{{0, 1}, {1, 2}, {2, 0}}
                 : std::vector<std::vector<int>>{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    std::map<std::vector<int>, int> count;
    for (Eigen::Index e = 0; e < mesh.num_elements(); ++e)
      for (const auto& f : local) {
        std::vector<int> key;
        for (int a : f) key.push_back(mesh.elements()(e, a));
        std::sort(key.begin(), key.end());
        ++count[key];
      }
    std::set<std::vector<int>> exterior, named;
    for (const auto& [key, n] : count) {
      EXPECT_LE(n, 2) << "a face shared by more than two simplices";
      if (n == 1) exterior.insert(key);
    }
    for (const std::string& name : mesh.boundary_names()) {
      const Connectivity& facets = mesh.boundary(name).facets;
      ASSERT_EQ(facets.cols(), dim);
      for (Eigen::Index f = 0; f < facets.rows(); ++f) {
        std::vector<int> key(facets.row(f).data(), facets.row(f).data() + dim);
        std::sort(key.begin(), key.end());
        EXPECT_EQ(count.count(key), 1u) << name << " facet " << f << " is not a face of the simplices";
        named.insert(key);
      }
    }
    EXPECT_EQ(named, exterior) << "the named faces must be exactly the exterior faces (a nonconforming split "
                                  "leaves interior faces of one simplex)";
  }
}

}  // namespace
}  // namespace frictopt::mesh
