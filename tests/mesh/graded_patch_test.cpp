// SPDX-License-Identifier: MIT
// Patch test on an in-plane graded, vertically graded (power law and "contact") and morphed
// structured grid (docs/case-format.md, "[mesh]"): Q1 cells reproduce every linear displacement
// field exactly on any mesh of convex cells, and so do the grid's cells split into P1 simplices
// ([mesh] element = "tri3"/"tet4") if the split is conforming, so a linear field prescribed on
// the whole boundary must come back exactly inside.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <limits>
#include <set>
#include <string>
#include <utility>

#include "frictopt/fem/linear_elasticity.hpp"
#include "frictopt/mesh/structured_mesh.hpp"

namespace frictopt::mesh {
namespace {

void expect_patch_test_passed(ElementFamily family) {
  for (const auto& [dim, contact_layers] : {std::pair{2, false}, std::pair{3, false}, std::pair{2, true}, std::pair{3, true}}) {
    SCOPED_TRACE(std::to_string(dim) + "D" + (contact_layers ? ", vertical grading contact" : ", power law"));
    const auto shape = dim == 2 ? shape::BezierShape::curve(1.0, 4) : shape::BezierShape::surface(1.0, 0.8, 3, 3);
    GridResolution resolution{{12, 10, 5}, 1.6};
    resolution.growth = 1.25;
    resolution.refine_box = std::array<double, 4>{0.35, 0.6, 0.3, 0.5};
    if (contact_layers) {  // equal layers down to 0.25 m, growing by <= 1.5 above
      resolution.grading = 1.0;
      resolution.cells[2] = 8;
      resolution.vertical_grading = VerticalGrading::kContact;
      resolution.fine_depth = 0.25;
      resolution.vertical_growth = 1.5;
    }
    resolution.element_family = family;
    const StructuredMesh grid(shape, 1.0, resolution);
    ASSERT_EQ(family_of(grid.mesh().element_kind()), family);
    const Mesh& mesh = grid.mesh();
    Eigen::VectorXd alpha = Eigen::VectorXd::Constant(shape.num_controls(), 0.1);
    alpha(1) = 0.25;  // a non-flat bottom: the cells are morphed, not only stretched
    const Eigen::MatrixXd X = mesh.positions(alpha);
    Eigen::MatrixXd gradient(dim, dim);
    if (dim == 2)
      gradient << 2e-3, -1e-3, 1e-3, 3e-3;
    else
      gradient << 2e-3, -1e-3, 5e-4, 1e-3, 3e-3, -2e-3, -4e-4, 1e-3, 2.5e-3;
    const Eigen::VectorXd offset = Eigen::VectorXd::LinSpaced(dim, 1e-3, -5e-4);
    const auto field = [&](int node) -> Eigen::VectorXd { return offset + gradient * X.row(node).transpose(); };
    std::set<int> boundary;
    for (const std::string& name : mesh.boundary_names())
      for (int node : mesh.boundary(name).nodes) boundary.insert(node);
    fem::PrescribedDofs dirichlet;
    for (int node : boundary) {
      const Eigen::VectorXd u = field(node);
      for (int c = 0; c < dim; ++c) {
        dirichlet.dofs.push_back(dim * node + c);
        dirichlet.values.push_back(u(c));
      }
    }
    fem::LinearElasticity problem(mesh, {2e11, 0.3, fem::PlaneModel::kPlaneStrain}, dirichlet, {});
    ASSERT_GT(problem.dofs().num_free(), 0);
    problem.assemble(X);
    ASSERT_EQ(problem.factorize(), Status::kConverged) << problem.factorization().message();
    const Eigen::VectorXd u = problem.solve();
    double worst = 0, scale = 0;
    for (int node = 0; node < mesh.num_nodes(); ++node) {
      const Eigen::VectorXd expected = field(node);
      worst = std::max(worst, (u.segment(dim * node, dim) - expected).norm());
      scale = std::max(scale, expected.norm());
    }
    // Exact up to the round-off of the solve (condition number of the graded stiffness ~1e4).
    EXPECT_LE(worst, 1e-11 * scale);
  }
}

TEST(GradedStructuredMesh, PassesThePatchTestIn2DAnd3D) { expect_patch_test_passed(ElementFamily::kTensorProduct); }

TEST(GradedStructuredMesh, PassesThePatchTestSplitIntoSimplices) { expect_patch_test_passed(ElementFamily::kSimplex); }

}  // namespace
}  // namespace frictopt::mesh
