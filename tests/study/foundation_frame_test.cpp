// SPDX-License-Identifier: MIT
// The foundation plane with any unit normal and offset (docs/theory/friction-frame.md §3): a
// problem rotated rigidly by R — mesh coordinates, design motion, Dirichlet data and tractions
// turned by R, the foundation normal R e_dim and its first axis R e1 — has the same contact forces
// (in the foundation's frame), the turned displacement, the same cost Θ and the same subgradient ξ
// as the unrotated one; an offset d shifts only the gap.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "common/test_bodies.hpp"
#include "frictopt/contact/contact_boundary.hpp"
#include "frictopt/contact/delassus.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/cost/cost_functional.hpp"
#include "frictopt/study/build_mesh.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::study {
namespace {

// A 3D block dragged and pressed by its top (prescribed displacement), dish-shaped bottom.
BodyDefinition block_3d(const contact::FrictionLaw& law) {
  BodyDefinition b = frictopt::testing::dish_block_3d(law, Eigen::Vector3d(2e-5, 1e-5, -1.2e-3));  // stick and slip
  b.resolution = {{6, 6, 3}, 1.0};
  return b;
}

// The structured mesh of `def` turned by R (positions and design motion), as an imported body
// whose design moves along the turned normal (the sweep extension reproduces the grid's V).
BodyDefinition rotated(const BodyDefinition& def, const Eigen::MatrixXd& R) {
  const int dim = static_cast<int>(R.rows());
  const mesh::Mesh grid = build_mesh(def);
  std::map<std::string, mesh::BoundarySet, std::less<>> sets;
  for (const std::string& name : grid.boundary_names()) sets[name] = grid.boundary(name);
  const Eigen::MatrixXd X = grid.reference_positions() * R.transpose();
  auto reference = std::make_shared<const mesh::Mesh>(grid.element_kind(), X, grid.elements(),
                                                      Eigen::SparseMatrix<double>(dim * grid.num_nodes(), 0), sets);
  BodyDefinition out = def;
  mesh::PlaneFrame frame = mesh::PlaneFrame::from_normal(R.col(dim - 1), dim == 3 ? Eigen::VectorXd(R.col(0)) : Eigen::VectorXd());
  out.imported_mesh = ImportedMeshDefinition{"rotated-grid", reference, {"bottom", frame, mesh::ExtensionKind::kSweep, {}}};
  for (auto& d : out.dirichlet)
    if (d.displacement.size()) d.displacement = R * d.displacement;
  for (auto& t : out.tractions) t.traction = R * t.traction;
  out.contact->foundation.frame = frame;
  return out;
}

// The same grid as an imported body in the standard frame (identical code path but for R).
BodyDefinition as_imported(const BodyDefinition& def) {
  return rotated(def, Eigen::MatrixXd::Identity(def.shape.dim(), def.shape.dim()));
}

Eigen::Matrix3d rotation_3d() {
  return (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()) *
          Eigen::AngleAxisd(-0.3, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

double relative(const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return (a - b).norm() / b.norm(); }

struct Outcome {
  BodyState state;
  Evaluation evaluation;  // compliance
  Evaluation slip;        // total slip: reads u_t in the foundation's frame
};

Outcome solve(const BodyDefinition& def) {
  ElasticBody body(def);
  ShapeOracle oracle(body, cost::make_compliance());
  Outcome out;
  out.evaluation = oracle.evaluate_design(def.initial_design);
  out.state = oracle.last_state();
  ShapeOracle slip_oracle(body, cost::make_total_slip(1e-9));
  out.slip = slip_oracle.evaluate_design(def.initial_design);
  return out;
}

// λ, q (in the frame), u (turned), Θ and ξ to 1e-9 relative. The two solves differ by the
// rounding of R and by the Delassus route (Schur factor vs solves with G): ~1e-13.
void expect_invariant(const BodyDefinition& def, const Eigen::MatrixXd& R, const std::string& name) {
  const int dim = static_cast<int>(R.rows());
  const Outcome a = solve(as_imported(def));
  const Outcome b = solve(rotated(def, R));
  ASSERT_TRUE(a.evaluation.ok) << a.evaluation.message;
  ASSERT_TRUE(b.evaluation.ok) << b.evaluation.message;
  const contact::ContactState& sa = a.state.contact->state;
  const contact::ContactState& sb = b.state.contact->state;
  const double e_lambda = relative(sb.normal_forces(), sa.normal_forces());
  const double e_z = relative(sb.z, sa.z);
  Eigen::VectorXd u_turned(a.state.displacement.size());
  for (Eigen::Index n = 0; n < u_turned.size() / dim; ++n)
    u_turned.segment(dim * n, dim) = R * a.state.displacement.segment(dim * n, dim);
  const double e_u = relative(b.state.displacement, u_turned);
  const double e_theta = std::abs(b.evaluation.value - a.evaluation.value) / std::abs(a.evaluation.value);
  const double e_xi = relative(b.evaluation.subgradient, a.evaluation.subgradient);
  ASSERT_TRUE(a.slip.ok && b.slip.ok) << a.slip.message << b.slip.message;
  const double e_slip = std::abs(b.slip.value - a.slip.value) / std::abs(a.slip.value);
  const double e_slip_xi = relative(b.slip.subgradient, a.slip.subgradient);
  std::printf("%s total slip: Θ %.1e, ξ %.1e\n", name.c_str(), e_slip, e_slip_xi);
  EXPECT_LE(e_slip, 1e-9);
  EXPECT_LE(e_slip_xi, 1e-9);
  std::printf("%s: λ %.1e, z %.1e, u %.1e, Θ %.1e, ξ %.1e (%d slip, %d stick)\n", name.c_str(), e_lambda, e_z, e_u,
              e_theta, e_xi, a.state.contact->resultants.num_slip, a.state.contact->resultants.num_stick);
  EXPECT_GT(a.state.contact->resultants.num_slip, 0);
  EXPECT_LE(e_lambda, 1e-9);
  EXPECT_LE(e_z, 1e-9);
  EXPECT_LE(e_u, 1e-9);
  EXPECT_LE(e_theta, 1e-9);
  EXPECT_LE(e_xi, 1e-9);
  // The global resultant turns with the body; the frame's components do not.
  // (Copied entry by entry: GCC 12 reports a false -Warray-bounds for dynamic heads of Vector3d.)
  Eigen::VectorXd fa(dim), fb(dim);
  for (int k = 0; k < dim; ++k)
    fa(k) = a.state.contact->resultants.global_force(k), fb(k) = b.state.contact->resultants.global_force(k);
  EXPECT_LE((fb - R * fa).norm(), 1e-9 * fa.norm());
  EXPECT_NEAR(b.state.contact->resultants.normal_force, a.state.contact->resultants.normal_force,
              1e-9 * a.state.contact->resultants.normal_force);
}

TEST(FoundationFrame, RotatedProblemIsInvariantWithAPolygonLaw3d) {
  expect_invariant(block_3d(contact::FrictionLaw::polygon({0.2, 0.45, 0.25, 0.4})), rotation_3d(), "3D 4-gon");
}

TEST(FoundationFrame, RotatedProblemIsInvariantWithAnEllipseLaw3d) {
  expect_invariant(block_3d(contact::FrictionLaw::ellipse(0.2, 0.4)), rotation_3d(), "3D ellipse");
}

TEST(FoundationFrame, RotatedProblemIsInvariant2d) {
  Eigen::Matrix2d R;
  const double a = 0.6;
  R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  expect_invariant(frictopt::testing::thesis_body_2d(contact::FrictionLaw::interval(0.15, 0.35), 12, 5), R, "2D interval");
}

// The offset d moves the plane along n: the gaps drop by d and nothing else changes.
TEST(FoundationFrame, OffsetShiftsOnlyTheGap) {
  const BodyDefinition def = as_imported(block_3d(contact::FrictionLaw::disc(0.3)));
  BodyDefinition shifted = def;
  shifted.contact->foundation.offset = -2e-4;  // the plane 0.2 mm lower: everything lifts off less
  ElasticBody a(def), b(shifted);
  const mesh::Mesh& m = a.mesh();
  const Eigen::MatrixXd X = m.positions(def.initial_design);
  const Eigen::VectorXd ga = a.contact_boundary()->gaps(X), gb = b.contact_boundary()->gaps(X);
  EXPECT_LE((gb - (ga.array() + 2e-4).matrix()).cwiseAbs().maxCoeff(), 1e-18);
  EXPECT_EQ(a.contact_boundary()->gap_jacobian(m), b.contact_boundary()->gap_jacobian(m));
  EXPECT_EQ(a.contact_boundary()->tributary_areas(), b.contact_boundary()->tributary_areas());
  EXPECT_FALSE(b.contact_boundary()->standard_foundation());
  EXPECT_TRUE(a.contact_boundary()->standard_foundation());
}

// G with a tilted frame: per node the rows −t1ᵀ, −t2ᵀ, nᵀ; times(), times_full(), matrix() and
// add_transpose_times() are the same operator and its transpose.
TEST(FoundationFrame, GHasTheFrameRowsAndItsTransposeIsConsistent) {
  const Eigen::Matrix3d R = rotation_3d();
  ElasticBody body(rotated(block_3d(contact::FrictionLaw::disc(0.3)), R));
  const contact::ContactBoundary& G = *body.contact_boundary();
  ASSERT_FALSE(G.standard_foundation());
  Eigen::Matrix3d F;
  F.row(0) = -R.col(0).transpose();
  F.row(1) = -R.col(1).transpose();
  F.row(2) = R.col(2).transpose();
  EXPECT_LE((G.frame_rows() - F).norm(), 1e-15);
  const Eigen::SparseMatrix<double> Gm = G.matrix();
  Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(G.num_free(), -1.0, 2.0);
  Eigen::VectorXd z = Eigen::VectorXd::LinSpaced(G.num_unknowns(), 0.5, -1.5);
  EXPECT_LE((Gm * v - G.times(v)).norm(), 1e-14 * v.norm());
  Eigen::VectorXd w = Eigen::VectorXd::Zero(G.num_free());
  G.add_transpose_times(z, w);
  EXPECT_LE((Eigen::VectorXd(Gm.transpose() * z) - w).norm(), 1e-14 * z.norm());
  // Node 0's block is F times its displacement.
  const int node = G.nodes()[0];
  Eigen::VectorXd full = Eigen::VectorXd::Zero(body.mesh().num_dofs());
  full.segment(3 * node, 3) = Eigen::Vector3d(0.3, -0.2, 0.7);
  EXPECT_LE((G.times_full(full).head(3) - F * Eigen::Vector3d(0.3, -0.2, 0.7)).norm(), 1e-15);
}

// The tilted foundation's dense M from the Schur factor (turn_delassus of the standard one)
// equals M = G A⁻¹ Gᵀ formed by solves with the tilted G.
TEST(FoundationFrame, TurnedSchurDelassusEqualsSolvesWithTheTiltedG) {
  ElasticBody body(rotated(block_3d(contact::FrictionLaw::disc(0.3)), rotation_3d()));
  const BodyState s = body.solve(body.definition().initial_design);
  ASSERT_TRUE(s.contact && s.contact->delassus_matrix);
  const Eigen::MatrixXd by_solves = contact::dense_delassus(body.elasticity().factorization(), *body.contact_boundary());
  const double error = (*s.contact->delassus_matrix - by_solves).norm() / by_solves.norm();
  std::printf("turned Schur M vs solves with G: %.1e\n", error);
  EXPECT_LE(error, 1e-12);
}

TEST(FoundationFrame, ThePetscEngineRefusesATiltedFoundationNamingIt) {
  BodyDefinition def = rotated(block_3d(contact::FrictionLaw::disc(0.3)), rotation_3d());
  def.engine.kind = StateEngine::kPetsc;
  try {
    ElasticBody body(def);
    ADD_FAILURE() << "the PETSc engine accepted a tilted foundation";
  } catch (const InvalidInput& e) {
    // A build without PETSc (the sanitizer build) refuses the engine itself first.
    if (std::string(e.what()).find("built without PETSc") != std::string::npos) GTEST_SKIP() << e.what();
    EXPECT_NE(std::string(e.what()).find("foundation: solver.engine = \"petsc\" supports the default foundation only"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace frictopt::study
