// SPDX-License-Identifier: MIT
// Case files with an imported body ([mesh] file = ..., docs/meshes.md): what they read into, and
// the bad inputs — each an InvalidInput naming the file, the field and the group.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "common/invalid_input.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::study {
namespace {

namespace fs = std::filesystem;
// Case texts are parsed as if they lived in tests/mesh/data (mesh paths are relative to the case).
const std::string kOrigin = (fs::path(FRICTOPT_SOURCE_DIR) / "tests/mesh/data/case.toml").string();

std::string block_case(const std::string& mesh_table, const std::string& part_key = "boundary = \"Top\"") {
  return "[geometry]\ndim = 3\n\n[mesh]\n" + mesh_table +
         "\n\n[material]\nyoung = 7e10\npoisson = 0.3\n\n[[dirichlet]]\n" + part_key +
         "\ndisplacement = [0.0, 0.0, -1e-4]\n\n[design]\ncontrol_points = [2, 2]\ninitial = 1e-5\n"
         "upper_bound = 1e-4\n\n[contact.friction]\nkind = \"isotropic\"\nmu = 0.3\nn = 8\n";
}

using testing::invalid_input_message;

TEST(GmshCase, ReadsAnImportedBodyWithExtentsFromTheMesh) {
  const io::CaseDescription c =
      io::parse_case(block_case("file = \"block41.msh\"\ncontact = \"Bottom\"\nextension = \"sweep\""), kOrigin);
  ASSERT_TRUE(c.body.imported_mesh.has_value());
  EXPECT_EQ(c.body.contact_surface, "Bottom");
  EXPECT_EQ(c.body.imported_mesh->motion.patch, "Bottom");
  EXPECT_EQ(c.body.imported_mesh->motion.extension, mesh::ExtensionKind::kSweep);
  EXPECT_EQ(c.body.shape.extents()[0], 1.0);
  EXPECT_EQ(c.body.shape.extents()[1], 1.0);
  EXPECT_EQ(c.body.height, 0.5);
  EXPECT_EQ(c.body.dirichlet[0].boundary, "Top");
  ElasticBody body(c.body);
  const BodyState s = body.solve(c.body.initial_design);
  EXPECT_EQ(s.summary.status, Status::kConverged) << s.summary.message;
  EXPECT_EQ(body.contact_boundary()->num_nodes(), 9);
}

// On a tilted foundation the design moves the patch along the
// foundation's normal (not along x3), and the chart lies in the foundation plane.
TEST(GmshCase, TiltedFoundationSetsTheDesignMotionsFrame) {
  const io::CaseDescription c = io::parse_case(
      block_case("file = \"block41.msh\"\ncontact = \"Bottom\"\nextension = \"sweep\"") +
          "\n[foundation]\nnormal = [0.1, 0.0, 1.0]\naxis1 = [1.0, 0.0, 0.0]\n",
      kOrigin);
  ASSERT_TRUE(c.body.imported_mesh.has_value());
  const Eigen::Vector3d n = Eigen::Vector3d(0.1, 0.0, 1.0).normalized();
  EXPECT_LE((c.body.imported_mesh->motion.frame.normal - n).norm(), 1e-15);
  EXPECT_LE((c.body.contact->foundation.frame.normal - n).norm(), 1e-15);
  ElasticBody body(c.body);
  const BodyState s = body.solve(c.body.initial_design);
  EXPECT_EQ(s.summary.status, Status::kConverged) << s.summary.message;
  // Each control point moves the patch's nodes along n: the motion's rows at a patch node are
  // parallel to n (zero component orthogonal to it).
  const Eigen::MatrixXd V(body.mesh().design_jacobian());
  ASSERT_GT(V.norm(), 0.0);
  for (int a = 0; a < body.mesh().num_nodes(); ++a)
    for (Eigen::Index j = 0; j < V.cols(); ++j) {
      const Eigen::Vector3d move(V(3 * a, j), V(3 * a + 1, j), V(3 * a + 2, j));
      EXPECT_LE((move - move.dot(n) * n).norm(), 1e-12 * (1.0 + move.norm())) << "node " << a;
    }
}

TEST(GmshCase, BadImportedBodiesAreInvalidInputNamingFileFieldAndGroup) {
  const auto message = [](const std::string& text) {
    return invalid_input_message([&] { (void)io::parse_case(text, kOrigin); });
  };
  const std::string unknown = message(block_case("file = \"block41.msh\"\ncontact = \"Contact\""));
  EXPECT_NE(unknown.find("mesh.contact = \"Contact\""), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("\"Back\", \"Bottom\", \"Front\", \"Left\", \"Right\", \"Top\""), std::string::npos) << unknown;

  const std::string missing = message(block_case("file = \"nothing.msh\"\ncontact = \"Bottom\""));
  EXPECT_NE(missing.find("mesh.file"), std::string::npos) << missing;
  EXPECT_NE(missing.find("nothing.msh: mesh file not found"), std::string::npos) << missing;

  // A .msh of tetrahedra only is subdivided (docs/meshes.md); mixed cell types are refused.
  const std::string mixed = message(block_case("file = \"mixed22.msh\"\ncontact = \"Bottom\""));
  EXPECT_NE(mixed.find("1 8-node hexahedra"), std::string::npos) << mixed;

  const std::string face = message(block_case("file = \"block41.msh\"\ncontact = \"Bottom\"", "face = \"top\""));
  EXPECT_NE(face.find("dirichlet[0].face is for the structured box"), std::string::npos) << face;

  const std::string group = message(block_case("file = \"block41.msh\"\ncontact = \"Bottom\"", "boundary = \"top\""));
  EXPECT_NE(group.find("dirichlet[0].boundary = \"top\""), std::string::npos) << group;
  EXPECT_NE(group.find("\"Top\""), std::string::npos) << group;

  const std::string sized = message(block_case("file = \"block41.msh\"\nsize = 0.1\ncontact = \"Bottom\""));
  EXPECT_NE(sized.find("mesh.size = 0.1 is only for a .geo file"), std::string::npos) << sized;

  const std::string dim = message("[geometry]\ndim = 2\n\n[mesh]\nfile = \"block41.msh\"\ncontact = \"Bottom\"\n");
  EXPECT_NE(dim.find("a 2D mesh as geometry.dim = 2; block41.msh holds a 3D body"), std::string::npos) << dim;

  const std::string edge_on = message(block_case("file = \"block41.msh\"\ncontact = \"Bottom\"\npatch = \"Left\""));
  EXPECT_NE(edge_on.find("design patch 'Left' has zero extent"), std::string::npos) << edge_on;

  const std::string extension = message(block_case("file = \"block41.msh\"\ncontact = \"Bottom\"\nextension = \"x\""));
  EXPECT_NE(extension.find("mesh.extension = \"x\"; expected one of laplace, sweep"), std::string::npos) << extension;
}

// A design patch that is not on the contact surface is refused when the body is built.
TEST(GmshCase, PatchOffTheContactSurfaceIsRefused) {
  const io::CaseDescription c =
      io::parse_case(block_case("file = \"block41.msh\"\ncontact = \"Top\"\npatch = \"Bottom\"", "boundary = \"Left\""),
                     kOrigin);
  const std::string message = invalid_input_message([&] { ElasticBody body(c.body); });
  EXPECT_NE(message.find("the design patch 'Bottom' is not part of the contact surface 'Top'"), std::string::npos)
      << message;
}

// Dirichlet parts that leave rigid-body motions free: refused when the body is built, naming the
// file and the groups, instead of a failed factorization (exit 3) at the first solve.
// Rigid motions the Dirichlet parts leave free: held by contact and friction when the case has
// [contact] (a floating body, as on the box; it was refused for imported bodies), refused
// without it, naming the file and the count.
TEST(GmshCase, RigidBodyModesLeftFreeFloatWithContactAndAreRefusedWithout) {
  const std::string components = "boundary = \"Top\"\ncomponents = [2]";  // only x3 fixed: 3 modes free
  const io::CaseDescription c = io::parse_case(
      block_case("file = \"block41.msh\"\ncontact = \"Bottom\"", components), kOrigin);
  EXPECT_EQ(ElasticBody(c.body).num_floating_modes(), 3);
  BodyDefinition without_contact = c.body;
  without_contact.contact.reset();
  const std::string message = invalid_input_message([&] { ElasticBody body(without_contact); });
  EXPECT_NE(message.find("block41.msh: the Dirichlet parts ('Top') leave 3 of the body's 6 rigid-body motions free"),
            std::string::npos)
      << message;
  // All components on the top: fixed.
  const io::CaseDescription fixed =
      io::parse_case(block_case("file = \"block41.msh\"\ncontact = \"Bottom\""), kOrigin);
  EXPECT_EQ(ElasticBody(fixed.body).num_floating_modes(), 0);
}

}  // namespace
}  // namespace frictopt::study
