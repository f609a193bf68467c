// SPDX-License-Identifier: MIT
// Hertz contact on a body imported from Gmsh (docs/meshes.md): the spherical cap of
// tests/data/hertz_cap.geo (curvature radius R = 2 m under a cylinder of radius 0.5 m),
// tetrahedra subdivided into hexahedra, or kept as P1 cells at a third of the size
// (hertz_cap_p1.geo: about the same unknowns), pressed on the rigid plane by moving its top down.
// Contact radius (moment of the nodal forces, and the profile fit) and peak pressure (the
// profile fit's intercept: no node is guaranteed at the apex of the unstructured mesh)
// against Hertz at the measured load; the issue asks for 2 % on the finest test mesh.
//
//   ./build/tests/study/study_gmsh_hertz_slow_test | grep '^|'
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "frictopt/mesh/design_extension.hpp"
#include "frictopt/mesh/gmsh_mesh.hpp"
#include "study/contact_validation.hpp"

namespace frictopt::study::validation {
namespace {

namespace fs = std::filesystem;

void expect_hertz_within_two_percent(const char* file, mesh::ElementFamily family, bool print_header) {
  constexpr double kRadius = 2.0, kYoung = 1e9, kPoisson = 0.3, kHeight = 0.5 + 2.0 - 1.9364916731037085;
  BodyDefinition b;
  b.name = "hertz-cap";
  b.height = kHeight;
  ImportedMeshDefinition imported;
  imported.file = fs::path(FRICTOPT_SOURCE_DIR) / "tests/data" / file;
  imported.reference =
      std::make_shared<const mesh::Mesh>(mesh::GmshMesh(imported.file, {.family = family}).take_mesh());
  ASSERT_EQ(mesh::family_of(imported.reference->element_kind()), family);
  imported.motion.patch = "Cap";
  // The design chart is the cap's bounding rectangle on the plane (as the case reader builds it).
  const mesh::PatchChart chart = mesh::patch_chart(*imported.reference, "Cap", mesh::PlaneFrame::standard(3));
  b.shape = shape::BezierShape::surface(chart.extents(0), chart.extents(1), 3, 3);
  b.imported_mesh = std::move(imported);
  b.contact_surface = "Cap";
  b.initial_design = Eigen::VectorXd::Zero(9);  // the cap as meshed
  b.admissible.upper_bound = 0.05;
  b.admissible.height = kHeight;
  b.material = {kYoung, kPoisson, fem::PlaneModel::kPlaneStrain};
  b.dirichlet = {{"Top", {}, Eigen::Vector3d(0.0, 0.0, -0.008)}};
  ContactDefinition contact;
  contact.law = contact::FrictionLaw::disc(0.0);
  contact.dense_delassus_max_unknowns = 12000;
  b.contact = contact;

  const Timer timer;
  ElasticBody body(b);
  const BodyState state = body.solve(b.initial_design);
  const double seconds = timer.seconds();
  ASSERT_EQ(state.summary.status, Status::kConverged) << state.summary.message;
  ASSERT_TRUE(state.contact.has_value());
  const contact::ContactBoundary& boundary = *body.contact_boundary();
  const Eigen::VectorXd lambda = state.contact->state.normal_forces();
  const Eigen::MatrixXd X = body.mesh().reference_positions();
  Eigen::VectorXd r(boundary.num_nodes());
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    const int node = boundary.nodes()[static_cast<std::size_t>(i)];
    r(i) = std::hypot(X(node, 0), X(node, 1));
  }
  const double load = lambda.sum();
  const HertzPrediction theory = hertz(3, load, kRadius, kYoung, kPoisson);
  const double a_moment = moment_radius(3, lambda, r);
  const ProfileFit fit = fit_hertz_profile(lambda.cwiseQuotient(boundary.tributary_areas()), r, a_moment, 0.8);
  int loaded = 0;
  double nearest = 1e300;
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    loaded += lambda(i) > 0;
    nearest = std::min(nearest, r(i));
  }
  if (print_header) {
    std::printf("| cells | free unknowns | contact nodes | loaded | P [N] | a Hertz [m] | a moment err | a fit err | p0 Hertz [Pa] | p0 fit err | nearest node to the apex [m] | KKT | time [s] |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  }
  std::printf("| %d %s | %d | %lld | %d | %.5e | %.5f | %+.2f%% | %+.2f%% | %.4e | %+.2f%% | %.4f | %.1e | %.1f |\n",
              body.mesh().num_elements(), std::string(mesh::to_string(body.mesh().element_kind())).c_str(),
              body.elasticity().dofs().num_free(),
              static_cast<long long>(boundary.num_nodes()), loaded, load, theory.radius,
              100 * (a_moment / theory.radius - 1), 100 * (fit.radius / theory.radius - 1), theory.pressure,
              100 * (fit.peak / theory.pressure - 1), nearest, state.contact->summary.kkt_residual, seconds);
  EXPECT_LE(state.contact->summary.kkt_residual, 1e-8);
  EXPECT_LE(rel(a_moment, theory.radius), 0.02);
  EXPECT_LE(rel(fit.radius, theory.radius), 0.02);
  EXPECT_LE(rel(fit.peak, theory.pressure), 0.02);
  EXPECT_GE(fit.points, 20);
}

TEST(HertzContactImported, SphericalCapMeshedByGmshWithinTwoPercent) {
  expect_hertz_within_two_percent("hertz_cap.geo", mesh::ElementFamily::kTensorProduct, true);
}

TEST(HertzContactImported, SphericalCapInP1TetrahedraWithinTwoPercent) {
  expect_hertz_within_two_percent("hertz_cap_p1.geo", mesh::ElementFamily::kSimplex, false);
}

}  // namespace
}  // namespace frictopt::study::validation
