// SPDX-License-Identifier: MIT
#include "common/invalid_input.hpp"
#include "frictopt/mesh/design_extension.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "frictopt/core/error.hpp"
#include "frictopt/mesh/gmsh_mesh.hpp"
#include "frictopt/mesh/structured_mesh.hpp"

namespace frictopt::mesh {
namespace {

namespace fs = std::filesystem;
const fs::path kData = fs::path(FRICTOPT_SOURCE_DIR) / "tests/mesh/data";

using testing::invalid_input_message;

// The sweep extension on the extruded block reproduces the structured grid's vertical morph
// node for node: the same V rows at the same coordinates.
TEST(DesignExtension, SweepReproducesTheStructuredGridsV) {
  const auto shape = shape::BezierShape::surface(1.0, 1.0, 3, 3);
  const Mesh grid = StructuredMesh(shape, 0.5, {{2, 2, 1}, 1.0}).take_mesh();
  const Mesh imported = with_design_motion(GmshMesh(kData / "block.geo").mesh(), shape,
                                           {.patch = "Bottom", .frame = {}, .extension = ExtensionKind::kSweep, .fixed = {}});
  const Eigen::MatrixXd Vg = grid.design_jacobian();
  const Eigen::MatrixXd Vi = imported.design_jacobian();
  ASSERT_EQ(Vg.cols(), 9);
  ASSERT_EQ(Vi.cols(), 9);
  for (int i = 0; i < grid.num_nodes(); ++i) {
    int match = -1;
    for (int j = 0; j < imported.num_nodes(); ++j)
      if ((imported.reference_positions().row(j) - grid.reference_positions().row(i)).norm() == 0.0) match = j;
    ASSERT_GE(match, 0) << "structured node " << i;
    EXPECT_LE((Vi.middleRows(3 * match, 3) - Vg.middleRows(3 * i, 3)).cwiseAbs().maxCoeff(), 1e-15) << "node " << i;
  }
}

// The Laplace extension of the Bernstein partition of unity (Σ_k basis_k = 1 on the patch),
// held at zero on the top and free on the side, is the harmonic 1 − z/h, which isoparametric Q1
// cells reproduce exactly on the block. (Not on the subdivided cylinder: its side is made of
// bilinear facets that are not vertical, so the natural condition there is not ∂u/∂r = 0 and
// the discrete extension differs from 1 − z/h by 6e-4 at the side; the patch and fixed values
// are checked there.)
TEST(DesignExtension, LaplaceExtensionReproducesTheLinearHarmonicFunction) {
  struct Body {
    fs::path file;
    double size, height, a;
  };
  for (const Body& body : {Body{kData / "block.geo", NAN, 0.5, 1.0}, Body{kData / "cylinder.geo", 0.2, 0.4, 1.0}}) {
    const Mesh reference = GmshMesh(body.file, {.size = body.size}).take_mesh();
    const auto shape = shape::BezierShape::surface(body.a, body.a, 4, 3);
    const Mesh mesh = with_design_motion(reference, shape,
                                         {.patch = "Bottom", .frame = {}, .extension = ExtensionKind::kLaplace, .fixed = {"Top"}});
    const Eigen::MatrixXd V = mesh.design_jacobian();
    const Eigen::MatrixXd& X = mesh.reference_positions();
    double worst = 0.0, worst_tangential = 0.0;
    for (int i = 0; i < mesh.num_nodes(); ++i) {
      worst = std::max(worst, std::abs(V.row(3 * i + 2).sum() - (1.0 - X(i, 2) / body.height)));
      worst_tangential = std::max(worst_tangential, V.middleRows(3 * i, 2).cwiseAbs().maxCoeff());
    }
    if (body.file.stem() == "block") {
      EXPECT_LT(worst, 1e-12);
    }
    EXPECT_EQ(worst_tangential, 0.0) << body.file;  // the motion is along the normal e3 only
    // The patch moves by the Bézier basis at its chart coordinates (bounding box origin).
    const PatchChart chart = patch_chart(reference, "Bottom", PlaneFrame::standard(3));
    for (int node : mesh.boundary("Bottom").nodes) {
      const Eigen::VectorXd s = X.row(node).head(2).transpose() - chart.origin;
      EXPECT_LE((V.row(3 * node + 2).transpose() - shape.basis(s)).cwiseAbs().maxCoeff(), 1e-15);
    }
    for (int node : mesh.boundary("Top").nodes) EXPECT_EQ(V.row(3 * node + 2).cwiseAbs().maxCoeff(), 0.0);
  }
}

// Trial designs: the minimum scaled Jacobian falls as the patch rises into the body, and a
// design that inverts a cell is refused by check_quality naming the Gmsh element.
TEST(DesignExtension, InvertingTrialDesignIsRefusedWithTheScaledJacobianReported) {
  const Mesh reference = GmshMesh(kData / "cylinder.geo", {.size = 0.2}).take_mesh();
  const auto shape = shape::BezierShape::surface(1.0, 1.0, 3, 3);
  const Mesh mesh = with_design_motion(reference, shape, {.patch = "Bottom", .frame = {}, .extension = ExtensionKind::kLaplace, .fixed = {"Top"}});
  const double q0 = mesh.min_scaled_jacobian(mesh.positions(Eigen::VectorXd::Zero(9)));
  Eigen::VectorXd alpha = Eigen::VectorXd::Zero(9);
  alpha(4) = 0.5;  // the centre bump
  const double q1 = mesh.min_scaled_jacobian(mesh.positions(alpha));
  EXPECT_GT(q1, 0.0);
  EXPECT_LT(q1, q0);
  alpha(4) = 2.0;  // five times the height: the bottom passes through the top
  EXPECT_LT(mesh.min_scaled_jacobian(mesh.positions(alpha)), 0.0);
  const std::string message = invalid_input_message([&] { mesh.check_quality(mesh.positions(alpha), "design 7"); });
  EXPECT_NE(message.find("inverted for the design 7"), std::string::npos) << message;
  EXPECT_NE(message.find("Gmsh element"), std::string::npos) << message;
}

TEST(DesignExtension, BadPatchesAreInvalidInput) {
  const Mesh reference = GmshMesh(kData / "block41.msh").take_mesh();
  const auto shape = shape::BezierShape::surface(1.0, 1.0, 3, 3);
  const std::string unknown = invalid_input_message([&] { (void)with_design_motion(reference, shape, {.patch = "Contact", .frame = {}, .extension = ExtensionKind::kLaplace, .fixed = {}}); });
  EXPECT_NE(unknown.find("expected one of Back, Bottom, Front, Left, Right, Top"), std::string::npos) << unknown;
  const std::string edge_on = invalid_input_message([&] { (void)with_design_motion(reference, shape, {.patch = "Left", .frame = {}, .extension = ExtensionKind::kLaplace, .fixed = {}}); });
  EXPECT_NE(edge_on.find("design patch 'Left' has zero extent along tangent axis 1"), std::string::npos) << edge_on;
  const std::string extents = invalid_input_message([&] {
    (void)with_design_motion(reference, shape::BezierShape::surface(2.0, 1.0, 3, 3), {.patch = "Bottom", .frame = {}, .extension = ExtensionKind::kLaplace, .fixed = {}});
  });
  EXPECT_NE(extents.find("expected the patch's extent 1 m"), std::string::npos) << extents;
  const std::string kind = invalid_input_message([] { (void)parse_extension_kind("elastic"); });
  EXPECT_NE(kind.find("expected one of laplace, sweep"), std::string::npos) << kind;
}

// A tilted foundation frame: the chart is taken in the frame's plane, the motion is along n.
TEST(DesignExtension, TiltedFrameMovesAlongItsNormal) {
  const Mesh reference = GmshMesh(kData / "block41.msh").take_mesh();
  const PlaneFrame frame = PlaneFrame::from_normal(Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(0, 1, 0));
  EXPECT_NEAR((frame.tangents.col(1) - Eigen::Vector3d(-1, 0, 0)).norm(), 0.0, 1e-15);  // e2 = n × e1
  const auto shape = shape::BezierShape::surface(1.0, 1.0, 2, 2);
  const Mesh mesh = with_design_motion(reference, shape, {.patch = "Bottom", .frame = frame, .extension = ExtensionKind::kSweep, .fixed = {}});
  // The origin of the chart in (e1, e2) = (x2, −x1) is (0, −1): node (1, 0, 0) has parameter
  // (0, 0) → moved by control point 0 only.
  int found = 0;
  for (int node : mesh.boundary("Bottom").nodes) {
    const Eigen::RowVector3d x = mesh.reference_positions().row(node);
    if (x.isApprox(Eigen::RowVector3d(1, 0, 0))) {
      EXPECT_EQ(mesh.design_jacobian().coeff(3 * node + 2, 0), 1.0);
      EXPECT_EQ(mesh.design_jacobian().coeff(3 * node + 2, 1), 0.0);
      ++found;
    }
  }
  EXPECT_EQ(found, 1);
}

}  // namespace
}  // namespace frictopt::mesh
