// SPDX-License-Identifier: MIT
// Loading plates (docs/theory/loading-plate.md): a face moved rigidly by a prescribed total force.
// The tied DOFs give the reduced stiffness PᵀAP; the contact carries exactly the prescribed force
// at every design (the design cannot unload the body); the body floats in the plate's tied
// directions, and the bordered adjoint and forward derivative of such a body match central
// differences; a body with a free rotation is refused for sensitivities.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>

#include "common/oracle_gradient.hpp"
#include "common/test_bodies.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/cost/cost_functional.hpp"
#include "frictopt/fem/loading_plate.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/mesh/structured_mesh.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/floating_body.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::study {
namespace {

using contact::FrictionLaw;

// A 0.1 × 0.1 × 0.05 m block with a dish-shaped bottom, pressed onto the foundation by a plate
// on its top: `force` [N] in the tied directions, `held` directions at rest.
BodyDefinition plate_block(const Eigen::Vector3d& force, std::vector<int> tied, std::vector<int> held,
                           const FrictionLaw& law = FrictionLaw::disc(0.3)) {
  BodyDefinition b;
  b.shape = shape::BezierShape::surface(0.1, 0.1, 3, 3);
  b.height = 0.05;
  b.resolution = {{6, 6, 3}, 1.0};
  b.material = {7e10, 0.33, fem::PlaneModel::kPlaneStrain};
  b.admissible.upper_bound = 1e-4;
  b.admissible.height = 0.05;
  b.initial_design.resize(9);
  b.initial_design << 4e-5, 2e-5, 4e-5, 2e-5, 1e-5, 2.5e-5, 4e-5, 2e-5, 3.5e-5;
  b.contact = testing::tight_contact(law);
  fem::LoadingPlate plate;
  plate.boundary = "top";
  plate.force = force;
  plate.tied = std::move(tied);
  plate.held = std::move(held);
  b.plates = {plate};
  return b;
}

TEST(LoadingPlate, TiedStiffnessIsTheProlongedOne) {
  // PᵀAP from the untied assembly equals the tied assembly (pattern and values), and Pᵀl.
  BodyDefinition def = plate_block(Eigen::Vector3d(0, 0, -1e3), {2}, {});
  def.plates[0].boundary = "right";  // opposite the clamp: no shared node
  const mesh::Mesh mesh = mesh::StructuredMesh(def.shape, def.height, def.resolution).take_mesh();
  const fem::PrescribedDofs clamp = fem::expand_dirichlet(mesh, {{"left", {}, {}}});
  const std::vector<fem::FaceTraction> loads = {{"right", Eigen::Vector3d(1e5, 2e5, -3e5)}};
  const auto ties = fem::plate_ties(mesh, def.plates);
  fem::LinearElasticity plain(mesh, def.material, clamp, loads);
  fem::LinearElasticity tied(mesh, def.material, clamp, loads, {}, ties);
  const Eigen::MatrixXd X = mesh.positions(def.initial_design);
  plain.assemble(X);
  tied.assemble(X);
  ASSERT_EQ(tied.dofs().num_free(), plain.dofs().num_free() - static_cast<int>(ties.front().size()) + 1);
  std::vector<Eigen::Triplet<double>> p;
  for (int i = 0; i < plain.dofs().num_free(); ++i)
    p.emplace_back(i, tied.dofs().free_index(plain.dofs().free_dofs()[static_cast<std::size_t>(i)]), 1.0);
  Eigen::SparseMatrix<double> P(plain.dofs().num_free(), tied.dofs().num_free());
  P.setFromTriplets(p.begin(), p.end());
  const Eigen::MatrixXd expected = Eigen::MatrixXd(P.transpose() * plain.stiffness() * P);
  const double scale = expected.cwiseAbs().maxCoeff();
  EXPECT_LE((Eigen::MatrixXd(tied.stiffness()) - expected).cwiseAbs().maxCoeff(), 1e-13 * scale);
  EXPECT_LE((tied.load() - P.transpose() * plain.load()).cwiseAbs().maxCoeff(), 1e-12 * plain.load().cwiseAbs().maxCoeff());
  // restrict_forces is Pᵀ, expand is P.
  const Eigen::VectorXd f = Eigen::VectorXd::LinSpaced(mesh.num_dofs(), -1.0, 2.0);
  EXPECT_LE((tied.dofs().restrict_forces(f) - P.transpose() * plain.dofs().restrict(f)).norm(), 1e-12);
  const Eigen::VectorXd ur = Eigen::VectorXd::LinSpaced(tied.dofs().num_free(), 0.5, 1.5);
  EXPECT_LE((plain.dofs().restrict(tied.dofs().expand(ur)) - P * ur).norm(), 1e-14);
}

// The contact carries the plate's force at every design: P = F to 1e-8, whatever the bottom.
TEST(LoadingPlate, TheContactCarriesThePrescribedForceAtEveryDesign) {
  const double F = 2e4;
  for (const bool lateral_tied : {false, true}) {
    SCOPED_TRACE(lateral_tied ? "x, y, z tied (shear 0.1 F in x)" : "z tied, x and y held");
    const BodyDefinition def = lateral_tied ? plate_block(Eigen::Vector3d(0.1 * F, 0, -F), {0, 1, 2}, {})
                                            : plate_block(Eigen::Vector3d(0, 0, -F), {2}, {0, 1});
    ElasticBody body(def);
    EXPECT_EQ(body.num_floating_modes(), lateral_tied ? 3 : 1);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> height(0.0, 8e-5);
    for (int k = 0; k < 5; ++k) {
      Eigen::VectorXd alpha = def.initial_design;
      if (k > 0)
        for (Eigen::Index i = 0; i < alpha.size(); ++i) alpha(i) = height(rng);
      const BodyState s = body.solve(alpha);
      ASSERT_EQ(s.summary.status, Status::kConverged) << s.summary.brief_report();
      const auto& res = s.contact->resultants;
      std::printf("design %d: P = %.12e N, T = (%.6e, %.6e) N, plate u_z = %.6e m, F_z = %.12e N\n", k,
                  res.normal_force, res.tangential_force(0), res.tangential_force(1), s.plates[0].displacement(2),
                  s.plates[0].force(2));
      EXPECT_NEAR(res.normal_force, F, 1e-8 * F);
      ASSERT_EQ(s.plates.size(), 1u);
      EXPECT_NEAR(s.plates[0].force(2), -F, 1e-8 * F);
      if (lateral_tied) {
        EXPECT_NEAR(-res.tangential_force(0), 0.1 * F, 1e-8 * F);
        EXPECT_NEAR(s.plates[0].force(0), 0.1 * F, 1e-8 * F);
      } else {
        EXPECT_EQ(s.plates[0].displacement(0), 0.0);
      }
      // Every node of the plate moves as one in the tied directions.
      for (int node : body.mesh().boundary("top").nodes)
        for (int c : def.plates[0].tied)
          EXPECT_NEAR(s.displacement(3 * node + c), s.plates[0].displacement(c), 1e-15);
    }
  }
}

// Θ's subgradient with a plate (the bordered adjoint) against central differences, for a body
// floating in z only and in x, y, z.
TEST(LoadingPlate, SubgradientMatchesCentralDifferences) {
  const double F = 2e4;
  for (const bool lateral_tied : {false, true}) {
    SCOPED_TRACE(lateral_tied ? "x, y, z tied" : "z tied, x and y held");
    // Floating in x, y, z under the 4-gon (vertex and ray slip rows); the disc's smooth-slip row
    // has λ Dw ∝ 1/|u_t|, and a node that barely slips made this piece singular (rcond 1e-18).
    const BodyDefinition def =
        lateral_tied ? plate_block(Eigen::Vector3d(0.05 * F, 0.02 * F, -F), {0, 1, 2}, {},
                                   FrictionLaw::polygon({0.3, 0.3, 0.3, 0.3}))
                     : plate_block(Eigen::Vector3d(0, 0, -F), {2}, {0, 1});
    {
      const bool compliance = lateral_tied;  // one cost per plate, both costs in all
      ElasticBody body(def);
      ShapeOracle oracle(body, compliance ? cost::make_compliance() : cost::make_normal_force_power(4.0));
      const Eigen::VectorXd alpha = def.initial_design;
      const Evaluation e = oracle.evaluate_design(alpha);
      ASSERT_TRUE(e.ok) << e.message << "; " << e.adjoint.brief_report() << "; " << e.index_sets.summary();
      const Eigen::VectorXd fd = testing::oracle_central_gradient(oracle, alpha);
      const double error = (e.subgradient - fd).norm() / fd.norm();
      std::printf("%s, %s: |xi| = %.6e, |fd| = %.6e, relative error %.2e\n", lateral_tied ? "xyz tied" : "z tied",
                  compliance ? "compliance" : "normal force power", e.subgradient.norm(), fd.norm(), error);
      EXPECT_LE(error, 1e-4);
    }
  }
}

// The forward derivative δu along h (bordered, with R δβ) against central differences of u.
TEST(LoadingPlate, StateDerivativeMatchesCentralDifferences) {
  const BodyDefinition def = plate_block(Eigen::Vector3d(0, 0, -2e4), {2}, {0, 1});
  ElasticBody body(def);
  ShapeOracle oracle(body, cost::make_normal_force_power(4.0));
  const Eigen::VectorXd alpha = def.initial_design;
  Eigen::VectorXd h = Eigen::VectorXd::LinSpaced(alpha.size(), -1.0, 1.0);
  (void)oracle.evaluate_design(alpha);
  const auto d = oracle.state_derivative(alpha, h);
  ASSERT_EQ(d.status, Status::kConverged);
  const double eps = 1e-4 * alpha.cwiseAbs().maxCoeff();
  const BodyState plus = body.solve(alpha + eps * h), minus = body.solve(alpha - eps * h);
  const Eigen::VectorXd du = (plus.displacement - minus.displacement) / (2 * eps);
  const Eigen::VectorXd dz = (plus.contact->state.z - minus.contact->state.z) / (2 * eps);
  std::printf("|du| = %.6e, error %.2e; |dz| = %.6e, error %.2e\n", du.norm(), (d.displacement - du).norm() / du.norm(),
              dz.norm(), (d.contact - dz).norm() / dz.norm());
  EXPECT_LE((d.displacement - du).norm(), 1e-4 * du.norm());
  EXPECT_LE((d.contact - dz).norm(), 1e-4 * dz.norm());
}

// A body whose free modes include a rotation: the sensitivity is refused, not wrong.
TEST(LoadingPlate, FloatingWithAFreeRotationRefusesSensitivities) {
  BodyDefinition def = plate_block(Eigen::Vector3d::Zero(), {2}, {});
  def.plates.clear();
  def.tractions = {{"top", Eigen::Vector3d(0.0, 0.0, -4e6)}};  // no Dirichlet condition: 6 free modes
  ElasticBody body(def);
  EXPECT_EQ(body.num_floating_modes(), 6);
  EXPECT_FALSE(body.elasticity().free_modes_are_translations());
  ShapeOracle oracle(body, cost::make_normal_force_power(4.0));
  const Evaluation& plain = oracle.evaluate_design(def.initial_design, false);
  ASSERT_TRUE(plain.ok) << plain.message;  // the state itself is solved
  try {
    (void)oracle.evaluate_design(def.initial_design, true);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("include a rotation"), std::string::npos) << e.what();
  }
  try {
    (void)oracle.state_derivative(def.initial_design, Eigen::VectorXd::Ones(9));
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("include a rotation"), std::string::npos) << e.what();
  }
}

TEST(LoadingPlate, FreeModesWithTiesKeepOnlyTranslations) {
  Eigen::MatrixXd X(4, 3);
  X << 0, 0, 1, 1, 0, 1, 0, 1, 1, 0, 0, 0;
  // The plate = the three nodes at z = 1, tied in z: rotations about x and y tilt it, so only
  // translations and the rotation about z remain.
  const Eigen::MatrixXd R = free_rigid_modes(X, {}, {{2, 5, 8}});
  EXPECT_EQ(R.cols(), 4);
  EXPECT_FALSE(modes_are_translations(R, 3));
  // Tied in x, y and z: translations only.
  const Eigen::MatrixXd T = free_rigid_modes(X, {}, {{0, 3, 6}, {1, 4, 7}, {2, 5, 8}});
  EXPECT_EQ(T.cols(), 3);
  EXPECT_TRUE(modes_are_translations(T, 3));
}

// cases3d/gmsh-punch (the demo imported from punch.geo) with its displacement-driven top replaced
// by a plate on the physical group "Top": the contact carries the force, at α⁰ and at a changed
// design, and Θ's subgradient matches central differences.
TEST(LoadingPlate, PlateOnAGmshGroup) {
  const std::filesystem::path source = std::filesystem::path(FRICTOPT_SOURCE_DIR) / "cases3d/gmsh-punch";
  const auto read = [](const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  };
  const auto replace = [](std::string& text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  // The punch on an 8 × 8 × 4 grid (the test's time), beside a case that names it.
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("frictopt_plate_gmsh_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::string geo = read(source / "punch.geo");
  replace(geo, "n1 = 16, n2 = 16, nv = 8", "n1 = 8, n2 = 8, nv = 4");
  std::ofstream(dir / "punch.geo") << geo;
  std::string toml = read(source / "case.toml");
  replace(toml, "[[dirichlet]]\nboundary = \"Top\"\ndisplacement = [1.0e-4, 0.0, -1.2e-3]",
          "[[plate]]\nboundary = \"Top\"\nforce = [0.0, 0.0, -3.0e7]\nheld = [\"x\", \"y\"]");
  const io::CaseDescription c = io::parse_case(toml, (dir / "case.toml").string());
  std::filesystem::remove_all(dir);
  BodyDefinition def = c.body;
  def.contact->coulomb = testing::tight_contact(def.contact->law).coulomb;
  ElasticBody body(def);
  EXPECT_EQ(body.num_floating_modes(), 1);
  Eigen::VectorXd bumped = def.initial_design;
  bumped(5) += 1e-3;
  for (const Eigen::VectorXd& alpha : {def.initial_design, bumped}) {
    const BodyState s = body.solve(alpha);
    ASSERT_EQ(s.summary.status, Status::kConverged) << s.summary.brief_report();
    std::printf("Gmsh punch: P = %.12e N, plate travel %.6e m\n", s.contact->resultants.normal_force,
                s.plates[0].displacement(2));
    EXPECT_NEAR(s.contact->resultants.normal_force, 3e7, 1e-8 * 3e7);
    EXPECT_NEAR(s.plates[0].force(2), -3e7, 1e-8 * 3e7);
  }
  // ξ·h against a central difference along one direction (the full gradient by differences is
  // LoadingPlate.SubgradientMatchesCentralDifferences' on the box).
  ShapeOracle oracle(body, cost::make_normal_force_power(4.0));
  const Evaluation e = oracle.evaluate_design(def.initial_design);
  ASSERT_TRUE(e.ok) << e.message;
  // One interior control point (a symmetric body: an antisymmetric h has ξ·h ≈ 0).
  const Eigen::VectorXd h = Eigen::VectorXd::Unit(def.initial_design.size(), 5);
  const double step = 1e-4 * def.initial_design.cwiseAbs().maxCoeff();
  const double fd = (oracle.evaluate_design(def.initial_design + step * h, false).value -
                     oracle.evaluate_design(def.initial_design - step * h, false).value) /
                    (2 * step);
  const double error = std::abs(e.subgradient.dot(h) - fd) / std::abs(fd);
  std::printf("Gmsh punch: xi.h = %.10e, central difference %.10e, relative error %.2e\n", e.subgradient.dot(h), fd,
              error);
  EXPECT_LE(error, 1e-4);
}

TEST(LoadingPlate, RefusesBadPlates) {
  const auto refuses = [](BodyDefinition def, const std::string& fragment) {
    try {
      ElasticBody body(def);
      ADD_FAILURE() << "expected InvalidInput with: " << fragment;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  BodyDefinition def = plate_block(Eigen::Vector3d(0, 0, -1e3), {2}, {0, 1});
  def.plates[0].boundary = "lid";
  refuses(def, "no boundary part \"lid\"");
  def = plate_block(Eigen::Vector3d(0, 0, -1e3), {2}, {2});
  refuses(def, "both held and tied");
  def = plate_block(Eigen::Vector3d(5.0, 0, -1e3), {2}, {0, 1});
  refuses(def, "holds");
  def = plate_block(Eigen::Vector3d(0, 0, -1e3), {2}, {0, 1});
  def.dirichlet = {{"left", {}, {}}};  // shares the edge nodes with the top
  refuses(def, "overlaps a Dirichlet condition");
  def = plate_block(Eigen::Vector3d(0, 0, -1e3), {2}, {0, 1});
  def.plates[0].boundary = "bottom";
  refuses(def, "contact surface");
  def = plate_block(Eigen::Vector3d(0, -1e3, 0), {1}, {});
  def.plates[0].force = Eigen::Vector2d(0, -1e3);
  refuses(def, "force has 2 entries; expected 3");
}

}  // namespace
}  // namespace frictopt::study
