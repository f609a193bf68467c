// SPDX-License-Identifier: MIT
// Physical validation of the contact solver through ElasticBody (docs/contact-validation.md), quick
// part: 2D Hertz convergence table, a coarse 3D Hertz check, Cattaneo–Mindlin stick zone,
// anisotropic gross sliding, μ = 0 = frictionless, split = fixed point, bad input. The 3D Hertz
// table and the n-gon → disc/ellipse convergence are in contact_validation_slow_test.cpp. Tables
// are printed (and copied to docs/contact-validation.md):
//   ./build/tests/study/study_test --gtest_filter='*' | grep '^|'
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/contact/delassus.hpp"
#include "frictopt/core/error.hpp"
#include "study/contact_validation.hpp"

namespace frictopt::study::validation {
namespace {

using contact::FrictionLaw;

// ---------------------------------------------------------------------------------------------
// Hertz, 2D plane strain.

// Block 1 m × 1 m, R = 2 m, E = 1 GPa, ν = 0.3, top pushed down 9 mm: a ≈ 0.106 m ≈ 0.11 of the
// width. Meshes of 50, 100, 200 cells across (a/h ≈ 5, 11, 21).
// Tolerance: 5% on a and p0 on the finest mesh, 10% on the coarser ones (the nodal
// pressure at a/h ≈ 5 carries O((h/a)²) lumping error). The remaining ≈ 0.7% on the finest mesh is
// the finite block (the half-space of Hertz theory is 1 m wide and 1 m deep here).
TEST(HertzContact2D, RadiusAndPeakPressureConvergeToHertzTheory) {
  std::printf("| mesh (cells) | a/h | P [N/m] | a Hertz [m] | a moment [m] | err | a fit [m] | err | p0 Hertz [Pa] | p peak [Pa] | err | KKT | time [s] |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const int cells : {50, 100, 200}) {
    BlockSpec s;
    s.dim = 2;
    s.cells = cells;
    s.layers = cells / 4;
    s.law = FrictionLaw::interval(0.0, 0.0);
    s.top_displacement = Eigen::Vector2d(0.0, -0.009);
    const Timer timer;
    ElasticBody body(block_definition(s));
    const BodyState state = body.solve(body.definition().initial_design);
    const double seconds = timer.seconds();
    SCOPED_TRACE("cells = " + std::to_string(cells));
    expect_valid_contact_state(body, state);
    const HertzMeasurement m = measure_hertz(body, state, s);
    print_hertz_row(m, cells, state, seconds);
    const double tol = cells == 200 ? 0.05 : 0.10;
    EXPECT_LE(rel(m.moment_radius, m.theory.radius), tol);
    EXPECT_LE(rel(m.fit.radius, m.theory.radius), tol);
    EXPECT_LE(rel(m.peak_pressure, m.theory.pressure), tol);
    // The loaded region must end where the theory says, to within one cell on either side.
    const double h = s.width / cells;
    EXPECT_LE(m.outermost_loaded, m.theory.radius + h);
    EXPECT_GE(m.innermost_unloaded, m.theory.radius - h);
    EXPECT_LE(m.theory.radius, 0.2 * s.width);
  }
}

// The 2D block above on the grid graded in-plane toward [0.35, 0.65] m (contact zone
// [0.394, 0.606]), growth 1.2, against the uniform grid of the same cells
// (docs/contact-validation.md §1b): the graded grid runs in 2D through the whole solve and meets
// the uniform grid's tolerances. Rows printed in the 2D table's format; docs/contact-validation.md,
// section 1b.
TEST(HertzContact2D, GradedGridMeetsTheToleranceAtEqualUnknowns) {
  for (const int cells : {50, 100}) {
    for (const bool graded : {false, true}) {
      BlockSpec s;
      s.dim = 2;
      s.cells = cells;
      s.layers = cells / 4;
      s.law = FrictionLaw::interval(0.0, 0.0);
      s.top_displacement = Eigen::Vector2d(0.0, -0.009);
      if (graded) {
        s.growth = 1.2;
        s.refine_min = 0.35;
        s.refine_max = 0.65;
      }
      const Timer timer;
      ElasticBody body(block_definition(s));
      const BodyState state = body.solve(body.definition().initial_design);
      const double seconds = timer.seconds();
      SCOPED_TRACE((graded ? "graded, cells = " : "uniform, cells = ") + std::to_string(cells));
      expect_valid_contact_state(body, state);
      const HertzMeasurement m = measure_hertz(body, state, s);
      std::printf("%s ", graded ? "graded 1.2" : "uniform   ");
      print_hertz_row(m, cells, state, seconds);
      EXPECT_LE(rel(m.moment_radius, m.theory.radius), 0.10);
      EXPECT_LE(rel(m.fit.radius, m.theory.radius), 0.10);
      EXPECT_LE(rel(m.peak_pressure, m.theory.pressure), 0.10);
      EXPECT_LE(m.outermost_loaded, m.theory.radius + m.cell);
      EXPECT_GE(m.innermost_unloaded, m.theory.radius - m.cell);
    }
  }
}

// Hertz, 3D, coarse: 24 × 24 × 8 hexahedra (a/h ≈ 3.7). The finer meshes and the table are in
// the slow binary. Tolerance 5%; at this resolution the errors are ≈ 1%.
TEST(HertzContact3D, CoarseMeshIsWithinFivePercentOfHertzTheory) {
  BlockSpec s;
  s.cells = 24;
  s.layers = 8;
  s.top_displacement = Eigen::Vector3d(0.0, 0.0, -0.012);
  ElasticBody body(block_definition(s));
  const BodyState state = body.solve(body.definition().initial_design);
  expect_valid_contact_state(body, state);
  const HertzMeasurement m = measure_hertz(body, state, s);
  std::printf("3D Hertz, 24 cells: a = %.4f (moment) vs %.4f (theory), p_peak = %.4e vs p0 = %.4e\n",
              m.moment_radius, m.theory.radius, m.peak_pressure, m.theory.pressure);
  EXPECT_LE(rel(m.moment_radius, m.theory.radius), 0.05);
  EXPECT_LE(rel(m.peak_pressure, m.theory.pressure), 0.05);
  EXPECT_LE(m.theory.radius, 0.2 * s.width);
}

// ---------------------------------------------------------------------------------------------
// Cattaneo–Mindlin partial slip, 2D.

// Reading of the loading (docs/contact-validation.md): the normal load is applied first without
// friction (the Hertz state u^H), then friction is switched on and the top is moved sideways by
// s. The slip of that step is u_t − u_t^H, so the step is the static Coulomb problem of
// ElasticBody with the tangential part of c shifted by u_t^H (∇_q = −(u_t − u_t^H)); M and c
// come from the body's own factorization. This is the loading for which Cattaneo–Mindlin
// holds. The one-step solve of ElasticBody (normal and tangential displacement of the top at
// once, slip counted from the unloaded body) is printed too: on a rigid foundation the normal
// load alone makes the body slip inward (Dundurs β = (1−2ν)/(2(1−ν)) = 0.29 ≠ 0), so its stick
// zone is ≈ 0.4a even for Q → 0 and Cattaneo–Mindlin does not apply to it.
//
// Stick half-width c, two estimators: (i) "edges": midway between the outermost stick node and
// its slipping neighbour on each side (error ≤ h/2 per edge); (ii) "moment": the deficit
// d_i = μλ_i − |q_i| is μ(p − |τ|) ≈ μ p0 (c/a) sqrt(1 − x²/c²) in the stick zone and 0 in the
// slip zone, so c = 2·sqrt(Σd_i(x_i − x̄)²/Σd_i) as for the Hertz radius.
// Tolerance: 10%. Expected deviation ≈ 5%: the tangential traction still changes the
// pressure through β (P grows by ≈ 0.2% and the stick zone moves by ≈ 0.1c).
TEST(CattaneoMindlin2D, StickZoneHalfWidthMatchesTheoryWithinTenPercent) {
  const double mu = 0.3;
  BlockSpec s;
  s.dim = 2;
  s.cells = 200;
  s.layers = 50;
  s.law = FrictionLaw::interval(0.0, 0.0);
  s.top_displacement = Eigen::Vector2d(0.0, -0.009);
  ElasticBody hertz_body(block_definition(s));
  const BodyState hertz_state = hertz_body.solve(hertz_body.definition().initial_design);
  expect_valid_contact_state(hertz_body, hertz_state);
  // M = G A⁻¹ Gᵀ depends on the mesh, the design and which DOFs are prescribed, not on the
  // prescribed values or the law: one M (the Hertz body's) serves every shift.
  const Eigen::MatrixXd M = hertz_state.contact->delassus_matrix
                                ? *hertz_state.contact->delassus_matrix
                                : contact::dense_delassus(hertz_body.elasticity().factorization(),
                                                          *hertz_body.contact_boundary());
  ASSERT_EQ(M.rows(), hertz_body.contact_boundary()->num_unknowns());
  const linalg::DenseOperator op(M);

  std::printf("| shift s [m] | Q/(μP) | a Hertz [m] | c theory [m] | c edges [m] | err | c moment [m] | err | stick/slip nodes | one-step: stick/slip, c edges [m] |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const double shift : {0.0025, 0.005, 0.0075}) {
    s.law = FrictionLaw::interval(mu, mu);
    s.top_displacement = Eigen::Vector2d(shift, -0.009);
    ElasticBody body(block_definition(s));
    const BodyState one_step = body.solve(body.definition().initial_design);
    expect_valid_contact_state(body, one_step);
    const contact::ContactBoundary& boundary = *body.contact_boundary();
    ASSERT_EQ(boundary.num_unknowns(), M.rows());
    Eigen::VectorXd c = linear_term(body, one_step);
    for (Eigen::Index i = 0; i < boundary.num_nodes(); ++i) c(2 * i) -= hertz_state.contact->state.gradient(2 * i);
    const contact::CoulombSolver solver(op, s.law, body.definition().contact->coulomb);
    contact::ContactState two_step;
    const auto summary = solver.solve(c, two_step);
    SCOPED_TRACE("shift = " + std::to_string(shift) + ": " + summary.brief_report());
    ASSERT_TRUE(summary.converged());
    EXPECT_LE(summary.kkt_residual, kResidualTolerance);
    EXPECT_LE(summary.complementarity_gap, kResidualTolerance);

    const Eigen::VectorXd x = boundary.plane_coordinates().col(0).array() - s.width / 2;
    const StickZone zone = measure_stick_zone(two_step, x, mu);
    const StickZone zone1 = measure_stick_zone(one_step.contact->state, x, mu);
    const double a = hertz(2, zone.normal_load, s.radius, s.young, s.poisson).radius;
    const double ratio = std::abs(zone.tangential_load) / (mu * zone.normal_load);
    const double c_theory = a * std::sqrt(1.0 - ratio);
    std::printf("| %.4f | %.3f | %.4f | %.4f | %.4f | %+.1f%% | %.4f | %+.1f%% | %d/%d | %d/%d, %.4f |\n", shift, ratio, a,
                c_theory, zone.edges_half_width, 100 * (zone.edges_half_width / c_theory - 1), zone.moment_half_width,
                100 * (zone.moment_half_width / c_theory - 1), zone.stick, zone.slip, zone1.stick, zone1.slip,
                zone1.edges_half_width);
    ASSERT_GT(zone.stick, 0);
    ASSERT_GT(zone.slip, 0);
    EXPECT_LT(ratio, 1.0);
    EXPECT_LE(rel(zone.edges_half_width, c_theory), 0.10);
    EXPECT_LE(rel(zone.moment_half_width, c_theory), 0.10);
  }
}

// ---------------------------------------------------------------------------------------------
// Anisotropic friction in gross sliding.

// The clamped top is moved by D = 0.1 m at angle θ (≈ 30 × the elastic tangential displacement
// at the onset of sliding) and pressed 12 mm: every loaded node slips. Each slipping node must
// satisfy normality, q_i = λ_i·w_i with w_i ∈ argmax_{w ∈ W} ⟨w, u_t^i⟩, i.e.
// ⟨q_i, u_t^i⟩ = λ_i N_W(u_t^i) and q_i ∈ λ_i W; so the total friction resistance Σq_i equals
// Σλ_i·exposed(u_t^i). For the polygons θ is chosen inside one normal-cone sector (away from
// the edge normals), so every node exposes the same vertex w_j and Σq_i = P·w_j: the friction
// force is μ(θ)·P with μ(θ) = w_j, whose component along the slip is the support function
// N_W(d_θ). For the ellipse the exposed point turns with the slip direction, so Σq_i is
// compared with Σλ_i·exposed(u_t^i) (exact) and with P·exposed(d_θ) (within the spread of
// slip directions, printed). Tolerance 1e-6 relative; the solver stops at 1e-10.
struct DragCase {
  std::string name;
  FrictionLaw law;
  double theta_degrees;
  bool single_vertex;
};

TEST(AnisotropicFriction, GrossSlidingTransmitsTheFrictionForceOfTheLaw) {
  const std::vector<DragCase> cases = {
      {"polygon n=4", FrictionLaw::polygon({0.2, 0.4, 0.2, 0.4}), 30.0, true},
      {"polygon n=4", FrictionLaw::polygon({0.2, 0.4, 0.2, 0.4}), 120.0, true},
      {"polygon n=8", FrictionLaw::polygon({0.3, 0.36, 0.42, 0.36, 0.3, 0.36, 0.42, 0.36}), 20.0, true},
      {"polygon n=8", FrictionLaw::polygon({0.3, 0.36, 0.42, 0.36, 0.3, 0.36, 0.42, 0.36}), 110.0, true},
      {"ellipse", FrictionLaw::ellipse(0.2, 0.4), 30.0, false},
      {"ellipse", FrictionLaw::ellipse(0.2, 0.4), 75.0, false},
  };
  std::printf("| law | θ [°] | P [N] | Σq [N] | μ(θ)·P [N] | rel. diff | N_W(d_θ) | Σq·d/P | max |normality| | slip-angle spread [°] |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const DragCase& dc : cases) {
    const double theta = dc.theta_degrees * std::numbers::pi / 180.0;
    const Eigen::Vector2d d(std::cos(theta), std::sin(theta));
    BlockSpec s;
    s.cells = 12;
    s.layers = 6;
    s.law = dc.law;
    s.top_displacement = Eigen::Vector3d(0.1 * d.x(), 0.1 * d.y(), -0.012);
    ElasticBody body(block_definition(s));
    const BodyState state = body.solve(body.definition().initial_design);
    SCOPED_TRACE(dc.law.describe() + ", theta = " + std::to_string(dc.theta_degrees));
    expect_valid_contact_state(body, state);
    const contact::ContactState& st = state.contact->state;
    Eigen::Vector2d total = Eigen::Vector2d::Zero(), predicted = Eigen::Vector2d::Zero();
    double load = 0, worst_normality = 0, min_angle = 1e9, max_angle = -1e9;
    for (Eigen::Index i = 0; i < st.num_nodes(); ++i) {
      const double lambda = st.lambda(i);
      total += st.q(i);
      load += lambda;
      if (st.is_separated(i)) continue;
      ASSERT_TRUE(st.is_slip(i)) << "node " << i << " does not slip";
      const Eigen::Vector2d u = st.u_t(i);
      predicted += lambda * dc.law.exposed_point(u);
      // Normality: ⟨q, u⟩ = λ N_W(u) (q exposes u) and q on the boundary of λW.
      const double normality = std::abs(st.q(i).dot(u) - lambda * dc.law.support(u)) / (lambda * u.norm());
      worst_normality = std::max(worst_normality, normality);
      EXPECT_LE(std::abs(dc.law.boundary_offset(st.q(i), lambda)), 1e-8 * lambda);
      const double angle = std::atan2(u.y(), u.x()) * 180.0 / std::numbers::pi;
      min_angle = std::min(min_angle, angle);
      max_angle = std::max(max_angle, angle);
      if (dc.single_vertex) {
        const auto& faces = st.nodes[static_cast<std::size_t>(i)].faces;
        EXPECT_EQ(faces.slip.face, contact::FrictionFace::kVertex);
        EXPECT_EQ(faces.force.face, contact::FrictionFace::kVertex);
      }
    }
    EXPECT_LE(worst_normality, 1e-8);
    const Eigen::Vector2d law_force = load * dc.law.exposed_point(d);
    EXPECT_LE((total - predicted).norm(), 1e-6 * predicted.norm());
    if (dc.single_vertex) {
      EXPECT_LE((total - law_force).norm(), 1e-6 * law_force.norm());
    }
    std::printf("| %s | %.0f | %.5e | (%.6e, %.6e) | (%.6e, %.6e) | %.1e | %.4f | %.6f | %.1e | %.2f |\n", dc.name.c_str(),
                dc.theta_degrees, load, total.x(), total.y(), law_force.x(), law_force.y(),
                (total - law_force).norm() / law_force.norm(), dc.law.support(d), total.dot(d) / load, worst_normality,
                max_angle - min_angle);
  }
}

// ---------------------------------------------------------------------------------------------
// μ = 0, split vs fixed point, residuals.

// Every law with zero coefficients is frictionless: q ≡ 0, and λ equals the disc(0) solve and
// an independent oracle, projected Gauss–Seidel on the dense normal block of M with c from
// A⁻¹l (forces unique: M_νν is SPD). Tolerance 1e-8 relative on λ: the QP stops at 1e-10
// relative projected gradient and M_νν has a condition number below 1e2 on these meshes.
TEST(ZeroFriction, EveryLawWithZeroCoefficientsReproducesFrictionlessContact) {
  struct Case {
    int dim;
    FrictionLaw law;
  };
  const std::vector<Case> cases = {{2, FrictionLaw::interval(0.0, 0.0)},  {3, FrictionLaw::disc(0.0)},
                                   {3, FrictionLaw::regular_polygon(0.0, 8)}, {3, FrictionLaw::polygon({0.0, 0.0, 0.0, 0.0})},
                                   {3, FrictionLaw::ellipse(0.0, 0.0)},       {3, FrictionLaw::ellipse_polygon(0.0, 0.0, 8)}};
  Eigen::VectorXd disc_lambda;
  for (const Case& cs : cases) {
    BlockSpec s;
    s.dim = cs.dim;
    s.cells = cs.dim == 2 ? 40 : 10;
    s.layers = cs.dim == 2 ? 10 : 5;
    s.law = cs.law;
    // A tangential motion of the top too: with μ = 0 it must not produce friction.
    s.top_displacement = cs.dim == 2 ? Eigen::VectorXd(Eigen::Vector2d(0.004, -0.012))
                                     : Eigen::VectorXd(Eigen::Vector3d(0.004, -0.002, -0.012));
    ElasticBody body(block_definition(s));
    const BodyState state = body.solve(body.definition().initial_design);
    SCOPED_TRACE(cs.law.describe());
    expect_valid_contact_state(body, state);
    const contact::ContactState& st = state.contact->state;
    EXPECT_EQ(tangential_forces(st).cwiseAbs().maxCoeff(), 0.0);
    constexpr int kMaxSweeps = 1000000;
    const OracleResult oracle = frictionless_oracle(body, state, kMaxSweeps);
    ASSERT_TRUE(oracle.converged) << "projected Gauss-Seidel stopped at its cap of " << kMaxSweeps << " sweeps";
    ASSERT_LT(oracle.sweeps, kMaxSweeps);
    const Eigen::VectorXd lambda = st.normal_forces();
    EXPECT_LE((lambda - oracle.lambda).norm(), 1e-8 * oracle.lambda.norm());
    EXPECT_GT(lambda.maxCoeff(), 0.0);
    // The 3D cases after the disc (listed first among them) are compared with its λ (same mesh).
    if (cs.law.kind() == contact::FrictionLawKind::kDisc) {
      disc_lambda = lambda;
    } else if (cs.dim == 3) {
      ASSERT_EQ(disc_lambda.size(), lambda.size()) << "the disc case must come first among the 3D cases";
      EXPECT_LE((lambda - disc_lambda).norm(), 1e-8 * disc_lambda.norm());
    }
  }
}

// The split variant (docs/theory/state-problem.md §6) and the full fixed point solve the same
// Coulomb problem; with partial slip and μ = 0.3 (2D interval, 3D disc and anisotropic polygon) the
// solution is unique here and both stop at 1e-10 relative increments: forces agree to 1e-7 relative
// (κ(M) ≲ 1e3 times the stopping tolerance). Also checks that each reports the method it used.
TEST(CoulombMethods, SplitVariantAndFullFixedPointAgree) {
  struct Case {
    int dim;
    FrictionLaw law;
  };
  const std::vector<Case> cases = {{2, FrictionLaw::interval(0.3, 0.3)},
                                   {2, FrictionLaw::interval(0.2, 0.4)},
                                   {3, FrictionLaw::disc(0.3)},
                                   {3, FrictionLaw::polygon({0.2, 0.4, 0.2, 0.4})}};
  for (const Case& cs : cases) {
    std::vector<Eigen::VectorXd> z;
    for (const auto method : {contact::CoulombMethod::kFixedPoint, contact::CoulombMethod::kSplit}) {
      BlockSpec s;
      s.dim = cs.dim;
      s.cells = cs.dim == 2 ? 40 : 10;
      s.layers = cs.dim == 2 ? 10 : 5;
      s.law = cs.law;
      s.method = method;
      s.top_displacement = cs.dim == 2 ? Eigen::VectorXd(Eigen::Vector2d(0.003, -0.012))
                                       : Eigen::VectorXd(Eigen::Vector3d(0.003, 0.0015, -0.012));
      ElasticBody body(block_definition(s));
      const BodyState state = body.solve(body.definition().initial_design);
      SCOPED_TRACE(cs.law.describe() + ", " + std::string(contact::to_string(method)));
      expect_valid_contact_state(body, state);
      EXPECT_EQ(state.contact->summary.method_used, method);
      const NodeCounts counts = count_nodes(state.contact->state);
      EXPECT_GT(counts.stick, 0);
      EXPECT_GT(counts.slip, 0);
      z.push_back(state.contact->state.z);
      std::printf("%s %s: %s\n", cs.law.describe().c_str(), std::string(contact::to_string(method)).c_str(),
                  state.contact->summary.brief_report().c_str());
    }
    const double diff = (z[0] - z[1]).norm() / z[0].norm();
    std::printf("%s: split vs fixed point, relative difference of z = %.2e\n", cs.law.describe().c_str(), diff);
    EXPECT_LE(diff, 1e-7) << cs.law.describe();
  }
}

// ---------------------------------------------------------------------------------------------
// Bad input and edge cases.

TEST(ElasticBodyInput, NoDirichletConditionThrowsNamingTheCause) {
  BlockSpec s;
  s.cells = 4;
  s.layers = 2;
  s.top_displacement = Eigen::Vector3d(0.0, 0.0, -0.01);
  BodyDefinition def = block_definition(s);
  def.dirichlet.clear();
  def.contact.reset();  // with contact the body floats (tests/study/floating_body_test.cpp)
  try {
    ElasticBody body(def);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("dirichlet"), std::string::npos) << what;
    EXPECT_NE(what.find("rigid-body"), std::string::npos) << what;
  }
}

// Only u_3 fixed on the top leaves three rigid modes (translations along x1, x2, rotation about
// x3). Without contact nothing holds them: InvalidInput naming the cause. With contact the body
// floats (docs/experiments.md §5): contact and friction hold it, solved with the kernel-aware dual;
// with no tangential load it reaches equilibrium with zero friction force.
TEST(ElasticBodyInput, DirichletConditionsLeavingRigidModes) {
  for (const bool with_contact : {false, true}) {
    BlockSpec s;
    s.cells = 4;
    s.layers = 2;
    s.top_displacement = Eigen::Vector3d(0.0, 0.0, -0.01);
    BodyDefinition def = block_definition(s);
    def.dirichlet = {{"top", {2}, Eigen::Vector3d(0.0, 0.0, -0.01)}};
    SCOPED_TRACE(with_contact ? "with contact" : "without contact");
    if (!with_contact) {
      def.contact.reset();
      try {
        ElasticBody body(def);
        FAIL() << "expected InvalidInput";
      } catch (const InvalidInput& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("3 rigid-body modes"), std::string::npos) << what;
      }
      continue;
    }
    ElasticBody body(def);
    EXPECT_EQ(body.num_floating_modes(), 3);
    const BodyState state = body.solve(def.initial_design);
    ASSERT_EQ(state.summary.status, Status::kConverged) << state.summary.brief_report();
    EXPECT_LE(state.contact->resultants.tangential_force_norm, 1e-8 * state.contact->resultants.normal_force);
  }
}

// A body lifted above the foundation touches nowhere: a valid, converged state with λ ≡ 0,
// q ≡ 0 and every node separated (2D and 3D, with friction).
TEST(ElasticBodyInput, BodyThatTouchesNowhereIsValidAndSeparated) {
  for (const int dim : {2, 3}) {
    BlockSpec s;
    s.dim = dim;
    s.cells = dim == 2 ? 20 : 6;
    s.layers = 4;
    s.law = dim == 2 ? FrictionLaw::interval(0.3, 0.3) : FrictionLaw::disc(0.3);
    s.top_displacement = Eigen::VectorXd::Zero(dim);
    s.top_displacement(0) = 0.002;
    s.top_displacement(dim - 1) = 0.005;  // lifted
    ElasticBody body(block_definition(s));
    const BodyState state = body.solve(body.definition().initial_design);
    SCOPED_TRACE("dim = " + std::to_string(dim));
    expect_valid_contact_state(body, state);
    const contact::ContactState& st = state.contact->state;
    EXPECT_EQ(st.z.cwiseAbs().maxCoeff(), 0.0);
    for (Eigen::Index i = 0; i < st.num_nodes(); ++i) {
      EXPECT_TRUE(st.is_separated(i));
      EXPECT_GT(st.normal_gap(i), 0.0);
    }
  }
}

// Symmetry planes: a quarter model of the Hertz problem prescribes u_1 = 0 on the left face and
// u_2 = 0 on the front face. The bottom nodes on those planes must stay contact nodes (their
// normal component is free); ContactBoundary drops every bottom node with any prescribed
// component (the A-BC rule for clamped nodes), which removes the apex from a quarter model.
TEST(ElasticBodySymmetry, BottomNodesWithAPrescribedComponentAreNotContactNodes) {
  // Documented limitation (docs/contact.md, "Contact nodes"): a bottom node with any
  // prescribed component — clamped (docs/theory/examples.md §2) or on a symmetry plane — is not a
  // contact node, so quarter/half models lose their symmetry-plane contact nodes; the validation
  // uses full models. This pins the behaviour so a change is noticed and documented.
  BlockSpec s;
  s.cells = 4;
  s.layers = 2;
  s.top_displacement = Eigen::Vector3d(0.0, 0.0, -0.01);
  BodyDefinition def = block_definition(s);
  def.dirichlet = {{"top", {2}, Eigen::Vector3d(0.0, 0.0, -0.01)},
                   {"left", {0}, Eigen::Vector3d::Zero()},
                   {"front", {1}, Eigen::Vector3d::Zero()}};
  ElasticBody body(def);
  const Eigen::Index all = (s.cells + 1) * (s.cells + 1);
  const Eigen::Index on_planes = 2 * (s.cells + 1) - 1;  // the x1 = 0 and x2 = 0 rows of the bottom
  EXPECT_EQ(body.contact_boundary()->num_nodes(), all - on_planes);
}

}  // namespace
}  // namespace frictopt::study::validation

namespace frictopt::study::validation {
namespace {

// ---------------------------------------------------------------------------------------------
// The contact patch test (docs/contact-validation.md §0): a flat block on the rigid plane, its top
// moved down by δ (vertical component only), the lateral rigid motions held at top corners. The
// exact solution is uniaxial stress, σ_33 = −E δ/H uniform (plane
// strain: E/(1 − ν²)), a linear
// displacement field; every element reproduces it, and consistent contact weights (∫ N_a over the
// contact facets: a quarter of a quadrilateral, a third of a triangle) then give every contact
// node the pressure λ_i/a_i = E δ/H exactly — on a graded grid whose facets all differ in size.
// Frictionless with ν = 0.3 (the bottom slides outward), and with the anisotropic 4-gon at ν = 0
// (nothing slides, all nodes stick).
TEST(ContactPatchTest, UniformPressureIsTransmittedExactlyByQ1AndP1Cells) {
  for (int dim : {2, 3})
    for (mesh::ElementFamily family : {mesh::ElementFamily::kTensorProduct, mesh::ElementFamily::kSimplex})
      for (bool friction : {false, true}) {
        SCOPED_TRACE(std::string(mesh::to_string(mesh::element_kind(family, dim))) +
                     (friction ? ", 4-gon friction, ν = 0" : ", frictionless, ν = 0.3"));
        constexpr double kDelta = 1e-3, kHeight = 0.8, kYoung = 1e9;
        BodyDefinition b;
        b.name = "contact-patch";
        b.shape = dim == 2 ? shape::BezierShape::curve(1.0, 3) : shape::BezierShape::surface(1.0, 0.7, 3, 3);
        b.height = kHeight;
        b.resolution.cells = {9, dim == 2 ? 1 : 7, 5};
        b.resolution.grading = 1.4;
        b.resolution.growth = 1.3;
        b.resolution.refine_box = std::array<double, 4>{0.3, 0.5, 0.2, 0.4};
        b.resolution.element_family = family;
        b.material = {kYoung, friction ? 0.0 : 0.3, fem::PlaneModel::kPlaneStrain};
        Eigen::VectorXd down = Eigen::VectorXd::Zero(dim);
        down(dim - 1) = -kDelta;
        b.dirichlet = {{"top", {dim - 1}, down}};
        // The lateral rigid motions held at two top corners, where the exact field u_i = ν δ x_i/H
        // (i < dim) vanishes in the components held (no contact node is constrained).
        const auto corner = [&](double x1, std::vector<int> components) {
          fem::NodalConstraint c;
          Eigen::VectorXd point = Eigen::VectorXd::Zero(dim);
          point(0) = x1;
          point(dim - 1) = kHeight;
          c.where.point = point;
          c.where.tolerance = 1e-9;
          c.components = std::move(components);
          return c;
        };
        b.constraints = {dim == 2 ? corner(0.0, {0}) : corner(0.0, {0, 1})};
        if (dim == 3) b.constraints.push_back(corner(1.0, {1}));
        b.initial_design = Eigen::VectorXd::Zero(b.shape.num_controls());
        b.admissible.upper_bound = 0.1;
        b.admissible.height = kHeight;
        ContactDefinition contact;
        if (dim == 2)
          contact.law = friction ? FrictionLaw::interval(0.4, 0.2) : FrictionLaw::interval(0.0, 0.0);
        else
          contact.law = friction ? FrictionLaw::polygon({0.4, 0.2, 0.4, 0.2}) : FrictionLaw::disc(0.0);
        b.contact = contact;
        ElasticBody body(b);
        const BodyState state = body.solve(b.initial_design);
        ASSERT_EQ(state.summary.status, Status::kConverged) << state.summary.message;
        const Eigen::VectorXd pressure =
            state.contact->state.normal_forces().cwiseQuotient(body.contact_boundary()->tributary_areas());
        // Uniaxial stress; in plane strain the modulus is E/(1 − ν²).
        const double nu = b.material.poisson;
        const double exact = (dim == 2 ? kYoung / (1 - nu * nu) : kYoung) * kDelta / kHeight;
        const double error = (pressure.array() - exact).abs().maxCoeff() / exact;
        std::printf("contact patch test, %s%s: %lld contact nodes, pressure %.6e Pa (exact %.6e), max error %.1e\n",
                    std::string(mesh::to_string(body.mesh().element_kind())).c_str(), friction ? ", friction" : "",
                    static_cast<long long>(pressure.size()), pressure.mean(), exact, error);
        EXPECT_LE(error, 1e-8);
        double tangential = 0.0;
        for (Eigen::Index i = 0; i < pressure.size(); ++i) tangential = std::max(tangential, state.contact->state.q(i).norm());
        EXPECT_LE(tangential, 1e-8 * state.contact->state.normal_forces().maxCoeff());
      }
}

}  // namespace
}  // namespace frictopt::study::validation
