// SPDX-License-Identifier: MIT
// Imported bodies through ElasticBody (docs/meshes.md): the patch test on an unstructured Gmsh
// mesh, the contact boundary's gap matrix and tributary areas on imported and structured meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>

#include "frictopt/core/error.hpp"
#include "frictopt/mesh/gmsh_mesh.hpp"
#include "frictopt/study/build_mesh.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::study {
namespace {

namespace fs = std::filesystem;
const fs::path kData = fs::path(FRICTOPT_SOURCE_DIR) / "tests/mesh/data";

// The cylinder of tests/mesh/data (radius 0.5, height 0.4), tetrahedra subdivided into hexahedra.
BodyDefinition cylinder_body(double size) {
  BodyDefinition b;
  b.name = "cylinder";
  b.shape = shape::BezierShape::surface(1.0, 1.0, 3, 3);  // the chart of the bottom disc: 1 m × 1 m
  b.height = 0.4;
  ImportedMeshDefinition imported;
  imported.file = kData / "cylinder.geo";
  imported.reference = std::make_shared<const mesh::Mesh>(mesh::GmshMesh(imported.file, {.size = size}).take_mesh());
  imported.motion.patch = "Bottom";
  b.imported_mesh = std::move(imported);
  b.contact_surface = "Bottom";
  b.initial_design = Eigen::VectorXd::Zero(9);
  b.admissible.upper_bound = 0.05;
  b.admissible.height = 0.4;
  return b;
}

// Patch test: with ν = 0, clamping the bottom and pushing the top down by δ gives the uniaxial
// strain u = (0, 0, −δ z/h), linear, which Q1 cells reproduce exactly on any mesh whose faces
// are the body's — here the distorted hexahedra of the subdivided box. (Not on the cylinder:
// its side is made of non-vertical bilinear facets, on which the exact field has a traction.)
TEST(GmshBody, PatchTestOnAnUnstructuredImportedMesh) {
  BodyDefinition b = cylinder_body(0.15);
  b.imported_mesh->file = kData / "box.geo";
  b.imported_mesh->reference =
      std::make_shared<const mesh::Mesh>(mesh::GmshMesh(b.imported_mesh->file, {.size = 0.15}).take_mesh());
  EXPECT_LT(b.imported_mesh->reference->min_scaled_jacobian(b.imported_mesh->reference->reference_positions()), 0.5);
  const double delta = 1e-3;
  b.material = {1e9, 0.0, fem::PlaneModel::kPlaneStrain};
  b.dirichlet = {{"Bottom", {}, Eigen::Vector3d::Zero()}, {"Top", {}, Eigen::Vector3d(0, 0, -delta)}};
  ElasticBody body(b);
  const BodyState state = body.solve(b.initial_design);
  ASSERT_EQ(state.summary.status, Status::kConverged) << state.summary.message;
  const Eigen::MatrixXd& X = body.mesh().reference_positions();
  double error = 0.0;
  for (int i = 0; i < body.mesh().num_nodes(); ++i) {
    const Eigen::Vector3d exact(0, 0, -delta * X(i, 2) / 0.4);
    error = std::max(error, (state.displacement.segment<3>(3 * i) - exact).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(error, 1e-12 * delta);
  EXPECT_EQ(state.min_scaled_jacobian, body.mesh().min_scaled_jacobian(X));
  EXPECT_GT(state.min_scaled_jacobian, 0.0);
  EXPECT_NEAR(state.strain_energy, 0.5 * 1e9 * (delta / 0.4) * (delta / 0.4) * state.volume, 1e-9 * state.strain_energy);
}

// The contact boundary on the imported disc: nodal areas ∫N_a sum to the area of the facets
// (the inscribed polygon of the disc, within 1% of π r² at this size), the gap matrix is the
// patch rows of V.
TEST(GmshBody, ContactBoundaryOfAnImportedDisc) {
  BodyDefinition b = cylinder_body(0.15);
  b.material = {1e9, 0.3, fem::PlaneModel::kPlaneStrain};
  b.dirichlet = {{"Top", {}, Eigen::Vector3d(0, 0, -1e-3)}};
  b.contact = ContactDefinition{};
  ElasticBody body(b);
  const contact::ContactBoundary& boundary = *body.contact_boundary();
  EXPECT_EQ(static_cast<std::size_t>(boundary.num_nodes()), body.mesh().boundary("Bottom").nodes.size());
  EXPECT_GT(boundary.tributary_areas().minCoeff(), 0.0);
  EXPECT_NEAR(boundary.tributary_areas().sum(), std::numbers::pi * 0.25, 0.01 * std::numbers::pi * 0.25);
  const Eigen::MatrixXd B = boundary.gap_jacobian(body.mesh());
  ASSERT_EQ(B.cols(), 9);
  // Bernstein partition of unity: every patch node's row sums to 1.
  EXPECT_LT((B.rowwise().sum().array() - 1.0).abs().maxCoeff(), 1e-14);
}

// On the structured grid the gap matrix from V is the Bézier gap matrix bit for bit (the oracle
// switched from the latter to the former; the structured cases' results must not move).
TEST(GmshBody, GapMatrixFromVIsTheStructuredGapMatrixBitForBit) {
  BodyDefinition b;
  b.shape = shape::BezierShape::surface(1.0, 0.8, 4, 3);
  b.height = 0.5;
  b.resolution = {{7, 5, 3}, 1.5};
  b.material = {7e10, 0.33, fem::PlaneModel::kPlaneStrain};
  b.dirichlet = {{"top", {}, Eigen::Vector3d(0, 0, -1e-3)}};
  b.contact = ContactDefinition{};
  b.initial_design = Eigen::VectorXd::Zero(12);
  b.admissible.upper_bound = 0.05;
  b.admissible.height = 0.5;
  ElasticBody body(b);
  const contact::ContactBoundary& boundary = *body.contact_boundary();
  const Eigen::MatrixXd from_v = boundary.gap_jacobian(body.mesh());
  const Eigen::MatrixXd bezier = b.shape.gap_matrix(boundary.plane_coordinates());
  ASSERT_EQ(from_v.rows(), bezier.rows());
  EXPECT_TRUE((from_v.array() == bezier.array()).all());
}

// A Gmsh part pressed by a force, with no clamp or with only its lateral motion held, is a
// floating body as on the box (contact and friction hold the free rigid motions); it was refused
// with "the Dirichlet parts () leave 6 of the body's 6 rigid-body motions free". The solve and
// its force balance: tests/study/gmsh_floating_slow_test.cpp. Without contact nothing holds them.
TEST(GmshBody, AnImportedBodyWithoutAClampFloatsOnItsContact) {
  BodyDefinition b = cylinder_body(0.25);
  b.material = {7e10, 0.33, fem::PlaneModel::kPlaneStrain};
  b.tractions = {{"Top", Eigen::Vector3d(0.0, 0.0, -1e6)}};
  b.contact = ContactDefinition{};
  b.contact->law = contact::FrictionLaw::disc(0.3);
  EXPECT_EQ(ElasticBody(b).num_floating_modes(), 6);
  b.dirichlet = {{"Top", {0, 1}, Eigen::Vector3d::Zero()}};
  EXPECT_EQ(ElasticBody(b).num_floating_modes(), 3);
  b.contact.reset();
  try {
    ElasticBody body(b);
    ADD_FAILURE() << "a body without contact whose rigid motions are free must be refused";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("leave 3 of the body's 6 rigid-body motions free"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace frictopt::study
