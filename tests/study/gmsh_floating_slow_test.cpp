// SPDX-License-Identifier: MIT
// A Gmsh part pressed by a force (docs/case-format.md, "[[dirichlet]]"): with no clamp, or with
// only its lateral motion held, contact and friction hold the free rigid motions — the floating
// body of the box (docs/experiments.md §5) on an imported mesh. The cylinder of tests/mesh/data
// (radius 0.5 m, height 0.4 m, 335 contact nodes at size 0.25) carries a pressure p on its top
// and a shear inside the friction capacity; the contact forces balance what the traction puts
// on the mesh. Slow: the augmented-Lagrangian solve on the subdivided tetrahedra takes about a
// minute per case.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "frictopt/mesh/gmsh_mesh.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::study {
namespace {

namespace fs = std::filesystem;

TEST(GmshFloatingBody, AnImportedBodyPressedByAForceIsHeldByItsContact) {
  const double p = 1e6, shear = 0.1 * p;  // |T| = P/10 < μP = 0.3 P
  for (const bool lateral_held : {false, true}) {
    SCOPED_TRACE(lateral_held ? "x1, x2 of the top held" : "no Dirichlet condition");
    BodyDefinition b;
    b.name = "cylinder";
    b.shape = shape::BezierShape::surface(1.0, 1.0, 3, 3);
    b.height = 0.4;
    ImportedMeshDefinition imported;
    imported.file = fs::path(FRICTOPT_SOURCE_DIR) / "tests/mesh/data/cylinder.geo";
    imported.reference = std::make_shared<const mesh::Mesh>(mesh::GmshMesh(imported.file, {.size = 0.25}).take_mesh());
    imported.motion.patch = "Bottom";
    b.imported_mesh = std::move(imported);
    b.contact_surface = "Bottom";
    b.initial_design = Eigen::VectorXd::Zero(9);
    b.admissible.upper_bound = 0.05;
    b.admissible.height = 0.4;
    b.material = {7e10, 0.33, fem::PlaneModel::kPlaneStrain};
    b.tractions = {{"Top", Eigen::Vector3d(lateral_held ? 0.0 : shear, 0.0, -p)}};
    if (lateral_held) b.dirichlet = {{"Top", {0, 1}, Eigen::Vector3d::Zero()}};
    ContactDefinition c;
    c.law = contact::FrictionLaw::disc(0.3);
    c.coulomb.relative_tolerance = 1e-10;
    c.coulomb.tresca.relative_tolerance = 1e-10;
    b.contact = c;
    ElasticBody body(b);
    EXPECT_EQ(body.num_floating_modes(), lateral_held ? 3 : 6);
    const BodyState s = body.solve(b.initial_design);
    ASSERT_EQ(s.summary.status, Status::kConverged) << s.summary.brief_report();
    std::printf("%s\n%s\n", s.contact->floating->brief_report().c_str(), s.summary.brief_report().c_str());
    // What the traction puts on the faceted top: the contact forces balance it.
    const Eigen::VectorXd l = body.elasticity().traction_load(s.positions);
    double applied_z = 0.0, applied_x = 0.0;
    for (Eigen::Index d = 2; d < l.size(); d += 3) applied_z += l(d);
    for (Eigen::Index d = 0; d < l.size(); d += 3) applied_x += l(d);
    const auto& res = s.contact->resultants;
    EXPECT_NEAR(res.normal_force, -applied_z, 1e-6 * std::abs(applied_z));
    EXPECT_NEAR(-applied_z, p * 0.785, 0.02 * p * 0.785);  // π r² of the inscribed polygon
    if (!lateral_held) {
      EXPECT_NEAR(-res.tangential_force(0), applied_x, 1e-6 * std::abs(applied_z));
    }
    EXPECT_GT(res.num_stick + res.num_slip, 0);
  }
}

}  // namespace
}  // namespace frictopt::study
