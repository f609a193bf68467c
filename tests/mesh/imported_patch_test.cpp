// SPDX-License-Identifier: MIT
// The full patch test on distorted imported meshes (docs/meshes.md): Q1 cells reproduce every
// affine displacement exactly on any mesh of convex cells, and P1 simplices on any mesh, so an affine field with a general
// gradient (stretch, shear and rotation in every direction), prescribed at every boundary
// node with ν = 0.3, must come back exactly at the interior nodes. The meshes are Gmsh's
// subdivisions of triangles (2D) and tetrahedra (3D) into quadrilaterals and hexahedra, whose
// cells are far from rectangular (minimum scaled Jacobian asserted below 0.7 in 2D, 0.5 in 3D;
// 1 for rectangles), and the same files' triangles and tetrahedra kept as P1 cells. Complements
// tests/study/gmsh_body_test.cpp (uniaxial strain through ElasticBody, ν = 0).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include "frictopt/fem/linear_elasticity.hpp"
#include "frictopt/mesh/gmsh_mesh.hpp"
#include "mesh/cell_boundary.hpp"

namespace frictopt::mesh {
namespace {

namespace fs = std::filesystem;
const fs::path kData = fs::path(FRICTOPT_SOURCE_DIR) / "tests/mesh/data";

// `distorted`: the minimum scaled Jacobian the mesh must stay below (1 for rectangular cells).
void expect_affine_fields_reproduced(const fs::path& file, double size, double distorted,
                                     ElementFamily family = ElementFamily::kTensorProduct) {
  const Mesh mesh = GmshMesh(file, {.size = size, .family = family}).take_mesh();
  ASSERT_EQ(family_of(mesh.element_kind()), family);
  const int dim = mesh.dim();
  const Eigen::MatrixXd& X = mesh.reference_positions();
  EXPECT_LT(mesh.min_scaled_jacobian(X), distorted) << "the mesh should be distorted";
  EXPECT_GT(mesh.min_scaled_jacobian(X), 0.0);
  Eigen::MatrixXd gradient(dim, dim);
  if (dim == 2)
    gradient << 2e-3, -1e-3, 1.5e-3, 3e-3;
  else
    gradient << 2e-3, -1e-3, 5e-4, 1e-3, 3e-3, -2e-3, -4e-4, 1e-3, 2.5e-3;
  const Eigen::VectorXd offset = Eigen::VectorXd::LinSpaced(dim, 1e-3, -5e-4);
  const auto field = [&](int node) -> Eigen::VectorXd { return offset + gradient * X.row(node).transpose(); };
  fem::PrescribedDofs dirichlet;
  const std::vector<int> boundary = testing::boundary_nodes(mesh);
  for (int node : boundary) {
    const Eigen::VectorXd u = field(node);
    for (int c = 0; c < dim; ++c) {
      dirichlet.dofs.push_back(dim * node + c);
      dirichlet.values.push_back(u(c));
    }
  }
  fem::LinearElasticity problem(mesh, {2e11, 0.3, fem::PlaneModel::kPlaneStrain}, dirichlet, {});
  ASSERT_GT(problem.dofs().num_free(), 100) << "interior nodes expected";
  problem.assemble(X);
  ASSERT_EQ(problem.factorize(), Status::kConverged) << problem.factorization().message();
  const Eigen::VectorXd u = problem.solve();
  double worst = 0, scale = 0;
  for (int node = 0; node < mesh.num_nodes(); ++node) {
    worst = std::max(worst, (u.segment(dim * node, dim) - field(node)).norm());
    scale = std::max(scale, field(node).norm());
  }
  std::printf("patch test %s: %d cells, %d free unknowns, max error %.2e of %.2e\n", file.filename().c_str(),
              mesh.num_elements(), problem.dofs().num_free(), worst, scale);
  EXPECT_LE(worst, 1e-10 * scale);
}

TEST(ImportedMeshPatchTest, AffineFieldsAreExactOnSubdividedTriangles) {
  expect_affine_fields_reproduced(kData / "mms_plate.geo", 0.08, 0.7);
}

TEST(ImportedMeshPatchTest, AffineFieldsAreExactOnSubdividedTetrahedra) {
  expect_affine_fields_reproduced(kData / "box.geo", 0.15, 0.5);
}

TEST(ImportedMeshPatchTest, AffineFieldsAreExactOnTrianglesKeptAsP1Cells) {
  expect_affine_fields_reproduced(kData / "mms_plate.geo", 0.08, 1.0, ElementFamily::kSimplex);
}

TEST(ImportedMeshPatchTest, AffineFieldsAreExactOnTetrahedraKeptAsP1Cells) {
  expect_affine_fields_reproduced(kData / "box.geo", 0.08, 1.0, ElementFamily::kSimplex);
}

}  // namespace
}  // namespace frictopt::mesh
