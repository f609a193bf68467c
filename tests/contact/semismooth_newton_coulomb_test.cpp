// SPDX-License-Identifier: MIT
// SemismoothNewtonCoulombSolver against the Coulomb fixed point (docs/contact.md, "Semismooth
// Newton"): the same solution to the solvers' tolerance and the same node classification for
// every friction set (2D interval, disc, regular and anisotropic polygons, ellipse, ellipse
// polygon) on random dual problems with stick, slip and separated nodes, by the dense-LU and by
// the GMRES steps; the automatic handover; the fallback; and a finite-element contact surface
// (13 × 13 bottom nodes pressed by a paraboloid and dragged) through the working-set solver.
#include "frictopt/contact/semismooth_newton_coulomb.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "contact/contact_test_problems.hpp"
#include "frictopt/contact/contact_boundary.hpp"
#include "frictopt/contact/delassus.hpp"
#include "frictopt/contact/working_set_coulomb.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/fem/linear_elasticity.hpp"
#include "frictopt/mesh/structured_mesh.hpp"

namespace frictopt::contact {
namespace {

struct Problem {
  Eigen::MatrixXd m;
  Eigen::VectorXd c;
};

Problem random_problem(int dim, Eigen::Index p, std::uint64_t seed) {
  std::mt19937_64 rng{seed};
  Problem problem;
  problem.m = testing::random_spd(dim * p, rng);
  problem.c = testing::random_c(dim, p, rng);
  return problem;
}

struct Counts {
  int stick = 0, slip = 0, separated = 0;
};
Counts count(const ContactState& s) {
  Counts n;
  for (Eigen::Index i = 0; i < s.num_nodes(); ++i) {
    n.stick += s.is_stick(i);
    n.slip += s.is_slip(i);
    n.separated += s.is_separated(i);
  }
  return n;
}

CoulombSolver::Options with_method(CoulombMethod method) {
  CoulombSolver::Options o;
  o.method = method;
  return o;
}

// Both solvers stop at 1e-10 (relative increment and inner QP projected gradient, resp. the
// projected gradient at s = λ); the solutions then agree to ≈ 1e-8 relative (the fixed point's
// increment test bounds its distance to the solution only up to the contraction factor).
constexpr double kAgreement = 1e-7;

void expect_same_solution(const ContactState& a, const ContactState& b, const std::string& what) {
  ASSERT_EQ(a.z.size(), b.z.size()) << what;
  const double scale = std::max(a.z.cwiseAbs().maxCoeff(), 1e-300);
  EXPECT_LE((a.z - b.z).cwiseAbs().maxCoeff() / scale, kAgreement) << what;
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    EXPECT_EQ(a.nodes[i].status, b.nodes[i].status) << what << ", node " << i;
    EXPECT_EQ(a.nodes[i].faces.force.face, b.nodes[i].faces.force.face) << what << ", node " << i;
    EXPECT_EQ(a.nodes[i].faces.slip.face, b.nodes[i].faces.slip.face) << what << ", node " << i;
    EXPECT_EQ(a.nodes[i].faces.slip.index, b.nodes[i].faces.slip.index) << what << ", node " << i;
  }
}

struct NamedLaw {
  std::string name;
  FrictionLaw law;
};

std::vector<NamedLaw> laws() {
  return {{"interval (2D)", FrictionLaw::interval(0.3, 0.5)},
          {"disc", FrictionLaw::disc(0.3)},
          {"regular 8-gon", FrictionLaw::regular_polygon(0.3, 8)},
          {"anisotropic 4-gon", FrictionLaw::polygon({0.2, 0.4, 0.2, 0.4})},
          {"anisotropic 6-gon turned", FrictionLaw::polygon({0.2, 0.35, 0.5, 0.45, 0.3, 0.25}).rotated(-0.7)},
          {"ellipse", FrictionLaw::ellipse(0.2, 0.4)},
          {"ellipse turned", FrictionLaw::ellipse(0.2, 0.6).rotated(0.9)},
          {"ellipse 12-gon", FrictionLaw::ellipse_polygon(0.2, 0.4, 12)}};
}

// Every law, both linear solvers (dense LU; GMRES with the single-precision LU preconditioner,
// forced by direct_max_unknowns = 0), cold and warm starts: Newton's z and classification are the
// fixed point's, the mixture holds stick, slip and separated nodes, and Newton converged itself.
TEST(SemismoothNewtonCoulomb, AgreesWithTheFixedPointForEveryLaw) {
  for (const NamedLaw& named : laws()) {
    const FrictionLaw& law = named.law;
    // The first of a few seeds whose solution mixes stick, slip and separated nodes.
    Problem problem;
    ContactState reference;
    bool mixed = false;
    for (std::uint64_t seed = testing::kSeed + 5; seed < testing::kSeed + 15 && !mixed; ++seed) {
      problem = random_problem(law.dim(), 40, seed);
      reference = ContactState();
      const CoulombSolver::Summary fp =
          CoulombSolver(linalg::DenseOperator(problem.m), law, with_method(CoulombMethod::kFixedPoint)).solve(problem.c, reference);
      ASSERT_TRUE(fp.converged()) << named.name << ": " << fp.brief_report();
      const Counts n = count(reference);
      mixed = n.stick > 0 && n.slip > 0 && n.separated > 0;
    }
    ASSERT_TRUE(mixed) << named.name << ": no seed gives stick, slip and separated nodes";
    const linalg::DenseOperator op(problem.m);
    for (const Eigen::Index direct_max : {Eigen::Index{600}, Eigen::Index{0}}) {
      CoulombSolver::Options o = with_method(CoulombMethod::kSemismoothNewton);
      o.newton.direct_max_unknowns = direct_max;
      const std::string what = named.name + (direct_max ? ", dense LU" : ", GMRES");
      ContactState state;
      const CoulombSolver::Summary s = CoulombSolver(op, law, o).solve(problem.c, state);
      ASSERT_TRUE(s.converged()) << what << ": " << s.brief_report() << " " << s.message;
      EXPECT_EQ(s.method_used, CoulombMethod::kSemismoothNewton) << what;
      EXPECT_FALSE(s.fallback) << what;
      EXPECT_GT(s.newton_iterations, 0) << what;
      EXPECT_LE(s.relative_projected_gradient, 1e-10) << what;
      EXPECT_LE(s.kkt_residual, 1e-8) << what;
      EXPECT_LE(s.complementarity_gap, 1e-8) << what;
      expect_same_solution(state, reference, what);
      // Warm start from the solution: converged at once.
      const CoulombSolver::Summary again = CoulombSolver(op, law, o).solve(problem.c, state);
      ASSERT_TRUE(again.converged()) << what;
      EXPECT_LE(again.newton_iterations, 1) << what;
      expect_same_solution(state, reference, what + ", warm");
    }
  }
}

// Frictionless (W = {0}) and a problem without contact (every c_ν > 0).
TEST(SemismoothNewtonCoulomb, FrictionlessAndNoContact) {
  for (const int dim : {2, 3}) {
    const FrictionLaw law = frictionless_law(dim);
    Problem problem = random_problem(dim, 30, testing::kSeed + 6);
    const linalg::DenseOperator op(problem.m);
    ContactState a, b;
    ASSERT_TRUE(CoulombSolver(op, law, with_method(CoulombMethod::kFixedPoint)).solve(problem.c, a).converged());
    ASSERT_TRUE(CoulombSolver(op, law, with_method(CoulombMethod::kSemismoothNewton)).solve(problem.c, b).converged());
    expect_same_solution(b, a, "frictionless, dim " + std::to_string(dim));
    for (Eigen::Index i = 0; i < 30; ++i) problem.c(dim * i + dim - 1) = 1.0 + 0.01 * static_cast<double>(i);
    ContactState none;
    const auto s = CoulombSolver(op, FrictionLaw::interval(0.3, 0.3).dim() == dim ? FrictionLaw::interval(0.3, 0.3)
                                                                                   : FrictionLaw::disc(0.3),
                                 with_method(CoulombMethod::kSemismoothNewton))
                       .solve(problem.c, none);
    ASSERT_TRUE(s.converged());
    EXPECT_EQ(none.z.cwiseAbs().maxCoeff(), 0.0);
  }
}

// kAutomatic: below automatic_min_unknowns the fixed point alone; above it, once the fixed point
// has used its budget of products, Newton finishes (reported), with the fixed point's solution.
TEST(SemismoothNewtonCoulomb, AutomaticHandsOverWhenLargeAndSlow) {
  const FrictionLaw law = FrictionLaw::disc(0.3);
  const Problem problem = random_problem(3, 40, testing::kSeed + 7);
  const linalg::DenseOperator op(problem.m);
  ContactState reference;
  ASSERT_TRUE(CoulombSolver(op, law, with_method(CoulombMethod::kFixedPoint)).solve(problem.c, reference).converged());

  CoulombSolver::Options o;  // the default is automatic
  EXPECT_EQ(o.method, CoulombMethod::kAutomatic);
  ContactState small;
  const auto s1 = CoulombSolver(op, law, o).solve(problem.c, small);
  ASSERT_TRUE(s1.converged());
  EXPECT_EQ(s1.method_given, CoulombMethod::kAutomatic);
  EXPECT_EQ(s1.method_used, CoulombMethod::kFixedPoint);  // 120 unknowns < 3000
  EXPECT_EQ(small.z, reference.z);                         // the fixed point's own result, bit for bit

  o.newton.automatic_min_unknowns = 100;
  o.newton.automatic_applications_per_unknown = 0.2;  // 24 products: fewer than the fixed point needs
  ContactState large;
  const auto s2 = CoulombSolver(op, law, o).solve(problem.c, large);
  ASSERT_TRUE(s2.converged()) << s2.message;
  EXPECT_EQ(s2.method_given, CoulombMethod::kAutomatic);
  EXPECT_EQ(s2.method_used, CoulombMethod::kSemismoothNewton);
  EXPECT_GT(s2.iterations, 0);  // fixed-point iterations before the handover
  EXPECT_GT(s2.newton_iterations, 0);
  EXPECT_NE(s2.message.find("handed over from the fixed point"), std::string::npos) << s2.message;
  expect_same_solution(large, reference, "automatic");
}

// A Newton that cannot converge (one step allowed) falls back to the fixed point and says so;
// without the fallback its status is returned.
TEST(SemismoothNewtonCoulomb, FallsBackToTheFixedPointAndReportsIt) {
  const FrictionLaw law = FrictionLaw::ellipse(0.2, 0.4);
  const Problem problem = random_problem(3, 40, testing::kSeed + 8);
  const linalg::DenseOperator op(problem.m);
  ContactState reference;
  ASSERT_TRUE(CoulombSolver(op, law, with_method(CoulombMethod::kFixedPoint)).solve(problem.c, reference).converged());
  CoulombSolver::Options o = with_method(CoulombMethod::kSemismoothNewton);
  o.newton.max_iterations = 1;
  ContactState state;
  const auto s = CoulombSolver(op, law, o).solve(problem.c, state);
  ASSERT_TRUE(s.converged());
  EXPECT_TRUE(s.fallback);
  EXPECT_EQ(s.method_given, CoulombMethod::kSemismoothNewton);
  EXPECT_EQ(s.method_used, CoulombMethod::kFixedPoint);
  EXPECT_NE(s.message.find("semismooth Newton failed"), std::string::npos) << s.message;
  EXPECT_NE(s.brief_report().find("Newton failed: fixed point"), std::string::npos) << s.brief_report();
  expect_same_solution(state, reference, "fallback");
  o.newton.fallback_to_fixed_point = false;
  ContactState alone;
  const auto t = CoulombSolver(op, law, o).solve(problem.c, alone);
  EXPECT_EQ(t.status, Status::kMaxIterations) << t.message;
  EXPECT_NE(t.message.find("newton.max_iterations = 1"), std::string::npos) << t.message;
}

TEST(SemismoothNewtonCoulomb, MethodSpellingsAndOptionChecks) {
  EXPECT_EQ(parse_coulomb_method("automatic"), CoulombMethod::kAutomatic);
  EXPECT_EQ(parse_coulomb_method("semismooth_newton"), CoulombMethod::kSemismoothNewton);
  EXPECT_EQ(to_string(CoulombMethod::kAutomatic), "automatic");
  CoulombSolver::Options o;
  o.method = CoulombMethod::kSemismoothNewton;
  EXPECT_NO_THROW(o.validate());  // the direct engine's Newton: no longer refused
  o.newton.gmres_max_iterations = 0;
  try {
    o.validate();
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("newton.gmres_max_iterations = 0; expected >= 1"), std::string::npos) << e.what();
  }
}

// A finite-element contact surface: a 12 × 12 × 3 box whose 13 × 13 bottom nodes are pressed by
// a paraboloid (the contact zone holds about a third of them) and dragged sideways, M from the
// Schur factor; the working-set solver with Newton and with the fixed point, and Newton on the
// whole dense M, give the same state and classification (what the sensitivity reads).
TEST(SemismoothNewtonCoulomb, FiniteElementSurfaceThroughTheWorkingSet) {
  const mesh::Mesh mesh =
      mesh::StructuredMesh(shape::BezierShape::surface(1.0, 1.0, 3, 3), 0.5, {{12, 12, 3}, 1.0}).take_mesh();
  fem::LinearElasticity fem(mesh, {1e9, 0.3, fem::PlaneModel::kPlaneStrain},
                            fem::expand_dirichlet(mesh, {{"top", {}, {}}}), {});
  const ContactBoundary boundary(mesh, fem.dofs());
  std::vector<int> trailing;
  for (Eigen::Index i = 0; i < boundary.num_nodes(); ++i)
    for (int c = 0; c < 3; ++c) trailing.push_back(boundary.free_dof(i, c));
  fem.set_trailing_dofs(trailing);
  fem.assemble(mesh.positions(Eigen::VectorXd::Zero(9)));
  ASSERT_EQ(fem.factorize(), Status::kConverged);
  const DenseDelassus dense(SchurDelassus(fem.factorization().trailing_factor(), 3).dense());
  const Eigen::MatrixXd& x = boundary.plane_coordinates();
  Eigen::VectorXd c = Eigen::VectorXd::Zero(boundary.num_unknowns());
  for (Eigen::Index i = 0; i < boundary.num_nodes(); ++i) {
    const double r2 = (x.row(i).array() - 0.5).square().sum();
    c(3 * i) = -2e-4;
    c(3 * i + 2) = r2 / (2 * 2.0) - 2e-3;
  }
  for (const NamedLaw& named : {NamedLaw{"disc", FrictionLaw::disc(0.3)},
                                NamedLaw{"anisotropic 4-gon", FrictionLaw::polygon({0.2, 0.4, 0.2, 0.4})},
                                NamedLaw{"ellipse", FrictionLaw::ellipse(0.2, 0.4)}}) {
    ContactState reference, working, whole;
    const auto fp = WorkingSetCoulombSolver(dense, named.law, with_method(CoulombMethod::kFixedPoint)).solve(c, reference);
    ASSERT_TRUE(fp.coulomb.converged()) << named.name;
    const Counts n = count(reference);
    EXPECT_GT(n.stick, 0) << named.name;
    EXPECT_GT(n.slip, 0) << named.name;
    EXPECT_GT(n.separated, 0) << named.name;
    const auto ws = WorkingSetCoulombSolver(dense, named.law, with_method(CoulombMethod::kSemismoothNewton)).solve(c, working);
    ASSERT_TRUE(ws.coulomb.converged()) << named.name << ": " << ws.coulomb.message;
    EXPECT_EQ(ws.coulomb.method_used, CoulombMethod::kSemismoothNewton) << named.name;
    expect_same_solution(working, reference, named.name + ", working set");
    CoulombSolver::Options gmres = with_method(CoulombMethod::kSemismoothNewton);
    gmres.newton.direct_max_unknowns = 0;
    const auto s = CoulombSolver(dense, named.law, gmres).solve(c, whole);
    ASSERT_TRUE(s.converged()) << named.name << ": " << s.message;
    EXPECT_FALSE(s.fallback) << named.name;
    expect_same_solution(whole, reference, named.name + ", whole M, GMRES");
  }
}

}  // namespace
}  // namespace frictopt::contact
