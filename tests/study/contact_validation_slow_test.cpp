// SPDX-License-Identifier: MIT
// Physical validation of the contact solver through ElasticBody (docs/contact-validation.md), slow
// part: the 3D Hertz convergence table (finest mesh 48 × 48 × 16 hexahedra) and the convergence of
// the n-gon laws to the disc and the ellipse. Tables (docs/contact-validation.md):
//   ./build/tests/study/study_slow_test | grep '^|'
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "frictopt/contact/contact_state.hpp"
#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/contact/delassus.hpp"
#include "frictopt/linalg/linear_operator.hpp"
#include "study/contact_validation.hpp"

namespace frictopt::study::validation {
namespace {

using contact::FrictionLaw;

// Hertz, 3D: the cube of side 1 m with the paraboloid R = 2 m at the centre of its base (full
// model: symmetry planes cannot be used, see docs/contact-validation.md), clamped top pushed
// down 12 mm, E = 1 GPa, ν = 0.3, μ = 0: a ≈ 0.156 m (0.16 of the width). Meshes 16, 32, 48
// cells across (a/h ≈ 2.5, 5, 7.5), 16/3 layers graded so the bottom layer is about one cell
// thick. Tolerance: 5% on a and p0 on the finest mesh, 10% on the coarser ones.
TEST(HertzContact3D, RadiusAndPeakPressureConvergeToHertzTheory) {
  std::printf("| mesh (cells) | a/h | P [N] | a Hertz [m] | a moment [m] | err | a fit [m] | err | p0 Hertz [Pa] | p peak [Pa] | err | KKT | time [s] |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const int cells : {16, 32, 48}) {
    BlockSpec s;
    s.cells = cells;
    s.layers = cells / 3;
    s.top_displacement = Eigen::Vector3d(0.0, 0.0, -0.012);
    const Timer timer;
    ElasticBody body(block_definition(s));
    const BodyState state = body.solve(body.definition().initial_design);
    const double seconds = timer.seconds();
    SCOPED_TRACE("cells = " + std::to_string(cells));
    expect_valid_contact_state(body, state);
    const HertzMeasurement m = measure_hertz(body, state, s);
    print_hertz_row(m, cells, state, seconds);
    const double tol = cells == 48 ? 0.05 : 0.10;
    EXPECT_LE(rel(m.moment_radius, m.theory.radius), tol);
    EXPECT_LE(rel(m.fit.radius, m.theory.radius), tol);
    EXPECT_LE(rel(m.peak_pressure, m.theory.pressure), tol);
    EXPECT_LE(m.outermost_loaded, m.theory.radius + m.cell);
    EXPECT_GE(m.innermost_unloaded, m.theory.radius - m.cell);
    EXPECT_LE(m.theory.radius, 0.2 * s.width);
  }
}

// Accuracy per unknown (docs/contact-validation.md §1b): the block above on the uniform grid and on
// the grid graded in-plane toward the square [0.3, 0.7]² m around the apex (growth 1.2; the contact
// zone is [0.344, 0.656]), with the same cells, hence the same unknowns. Errors: a (profile fit and
// moment) and p0 against Hertz for the measured load; the load P against the finest graded
// grid's (a finite block has no closed-form load for a prescribed top displacement).
// Table in docs/contact-validation.md:
//   ./build/tests/study/study_slow_test --gtest_filter='*GradedGrid*' | grep '^|'
TEST(HertzContact3D, GradedGridIsMoreAccuratePerUnknown) {
  struct Row {
    int cells;
    bool graded;
    int unknowns;
    HertzMeasurement m;
    double seconds;
  };
  std::vector<Row> rows;
  for (const bool graded : {false, true})
    for (const int cells : {16, 24, 32, 48}) {
      BlockSpec s;
      s.cells = cells;
      s.layers = cells / 3;
      s.top_displacement = Eigen::Vector3d(0.0, 0.0, -0.012);
      if (graded) {
        s.growth = 1.2;
        s.refine_min = 0.3;
        s.refine_max = 0.7;
      }
      const Timer timer;
      ElasticBody body(block_definition(s));
      const BodyState state = body.solve(body.definition().initial_design);
      const double seconds = timer.seconds();
      SCOPED_TRACE((graded ? "graded, cells = " : "uniform, cells = ") + std::to_string(cells));
      expect_valid_contact_state(body, state);
      rows.push_back({cells, graded, body.mesh().num_dofs(), measure_hertz(body, state, s), seconds});
    }
  const double reference_load = rows.back().m.load;
  std::printf("| grid | cells | unknowns | h at apex [m] | a/h | a fit err | a moment err | p0 peak err | P [N] | P vs finest graded | time [s] |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Row& r : rows)
    std::printf("| %s | %d | %d | %.4f | %.1f | %+.2f%% | %+.2f%% | %+.2f%% | %.5e | %+.3f%% | %.1f |\n",
                r.graded ? "graded 1.2" : "uniform", r.cells, r.unknowns, r.m.cell, r.m.theory.radius / r.m.cell,
                100 * (r.m.fit.radius / r.m.theory.radius - 1), 100 * (r.m.moment_radius / r.m.theory.radius - 1),
                100 * (r.m.peak_pressure / r.m.theory.pressure - 1), r.m.load, 100 * (r.m.load / reference_load - 1),
                r.seconds);
  // What the table shows (docs/contact-validation.md, section 1b): the radius by the profile fit,
  // which samples the pressure inside the contact zone, gains from the finer box cells at equal
  // unknowns from 24 cells on; every graded grid stays within the uniform grid's tolerances.
  const std::size_t levels = rows.size() / 2;
  for (std::size_t i = 0; i < levels; ++i) {
    const Row& uniform = rows[i];
    const Row& graded = rows[levels + i];
    SCOPED_TRACE("cells = " + std::to_string(graded.cells));
    ASSERT_EQ(graded.unknowns, uniform.unknowns);
    const double tol = graded.cells == 48 ? 0.05 : 0.10;
    EXPECT_LE(rel(graded.m.fit.radius, graded.m.theory.radius), tol);
    EXPECT_LE(rel(graded.m.moment_radius, graded.m.theory.radius), tol);
    EXPECT_LE(rel(graded.m.peak_pressure, graded.m.theory.pressure), tol);
    if (graded.cells >= 24) {
      EXPECT_LT(rel(graded.m.fit.radius, graded.m.theory.radius), rel(uniform.m.fit.radius, uniform.m.theory.radius));
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Regular n-gon → disc, ellipse polygon → ellipse.

// A small 3D problem with partial slip: 20 × 20 × 10 cells, the paraboloid pressed 12 mm and
// dragged (3, 1.5) mm, μ = 0.3 (resp. μ_x = 0.2, μ_y = 0.4): about 15 stick and 22 slip nodes.
// Expected rates (docs/contact-validation.md): the polygon with vertices on ∂W is inside W at
// Hausdorff distance d_n = O(1/n²) (μ(1 − cos(π/n)) for the disc). The dual energy
// J(z) = ½zᵀMz + cᵀz of a strongly convex QP moves by O(d_n) when the feasible set moves by
// d_n: rate 2. The minimizer itself only moves by O(sqrt(d_n)) = O(1/n) in general: at a
// slipping node q = λ·w_j is the vertex exposed by u_t, whose direction differs from u_t by up
// to π/n, so λ and q converge at rate 1 (observed 0.9–1.2), not 2.
// Checks: least-squares rate over n = 8..128 ≥ 0.8 for the forces (max of the λ and q errors)
// and ≥ 1.7 for J; forces at n = 128 at least 8× (J: 100×) closer than at n = 8.
// The exact law is solved through ElasticBody; M and c depend on the mesh and the load only, so
// each polygon is solved by CoulombSolver on the same dense M (the body's own) and c, exactly
// the solve ElasticBody would do for it (cold start, same options), and its Coulomb residuals
// are recomputed from ∇ = Mz + c.
void expect_polygon_convergence(const FrictionLaw& exact, const std::vector<FrictionLaw>& polygons,
                                const std::vector<int>& sides) {
  BlockSpec s;
  s.cells = 20;
  s.layers = 10;
  s.top_displacement = Eigen::Vector3d(0.003, 0.0015, -0.012);
  s.law = exact;
  ElasticBody exact_body(block_definition(s));
  const BodyState reference = exact_body.solve(exact_body.definition().initial_design);
  expect_valid_contact_state(exact_body, reference);
  const contact::ContactState& ref = reference.contact->state;
  const NodeCounts counts = count_nodes(ref);
  std::printf("%s: %d stick, %d slip, %d separated nodes\n", exact.describe().c_str(), counts.stick, counts.slip,
              counts.separated);
  ASSERT_GT(counts.stick, 0);
  ASSERT_GT(counts.slip, 0);
  // M and c depend on the mesh and the load only, not on the law.
  const Eigen::MatrixXd M =
      reference.contact->delassus_matrix
          ? *reference.contact->delassus_matrix
          : contact::dense_delassus(exact_body.elasticity().factorization(), *exact_body.contact_boundary());
  const Eigen::VectorXd c = linear_term(exact_body, reference);
  const linalg::DenseOperator op(M);
  const auto& options = exact_body.definition().contact->coulomb;
  const double c_scale = c.lpNorm<Eigen::Infinity>();
  const auto energy = [&](const Eigen::VectorXd& z) { return 0.5 * z.dot(M * z) + c.dot(z); };
  const double J_ref = energy(ref.z);
  const Eigen::VectorXd q_ref = tangential_forces(ref);
  std::printf("| exact law | n | rel. error λ | rate | rel. error q | rate | rel. error J | rate | time [s] |\n|---|---|---|---|---|---|---|---|---|\n");
  std::vector<double> log_n, log_lambda, log_q, log_force, log_energy;
  for (std::size_t k = 0; k < polygons.size(); ++k) {
    const Timer timer;
    const contact::CoulombSolver solver(op, polygons[k], options);
    contact::ContactState st(3, exact_body.contact_boundary()->num_nodes());  // cold start, as ElasticBody
    const contact::CoulombSolver::Summary summary = solver.solve(c, st);
    SCOPED_TRACE(polygons[k].describe() + ": " + summary.brief_report());
    ASSERT_TRUE(summary.converged());
    EXPECT_LE(summary.kkt_residual, kResidualTolerance);
    EXPECT_LE(summary.complementarity_gap, kResidualTolerance);
    const Eigen::VectorXd gradient = M * st.z + c;
    EXPECT_LE((gradient - st.gradient).lpNorm<Eigen::Infinity>(), 1e-10 * gradient.lpNorm<Eigen::Infinity>());
    const std::vector<FrictionLaw> laws = {polygons[k]};
    const contact::ContactResiduals r =
        contact::contact_residuals(laws, st.normal_forces(), st.z, gradient, st.dim, c_scale);
    EXPECT_LE(r.kkt_residual, kResidualTolerance);
    EXPECT_LE(r.complementarity_gap, kResidualTolerance);
    const double el = (st.normal_forces() - ref.normal_forces()).norm() / ref.normal_forces().norm();
    const double eq = (tangential_forces(st) - q_ref).norm() / q_ref.norm();
    const double eJ = std::abs(energy(st.z) - J_ref) / std::abs(J_ref);
    const double seconds = timer.seconds();
    const auto rate = [&](const std::vector<double>& logs, double e) {
      return k == 0 ? std::string() : fmt_rate((logs.back() - std::log(e)) / std::log(2.0));
    };
    std::printf("| %s | %d | %.3e | %s | %.3e | %s | %.3e | %s | %.1f |\n", exact.describe().c_str(), sides[k], el,
                rate(log_lambda, el).c_str(), eq, rate(log_q, eq).c_str(), eJ, rate(log_energy, eJ).c_str(), seconds);
    log_lambda.push_back(std::log(el));
    log_q.push_back(std::log(eq));
    log_n.push_back(std::log(sides[k]));
    log_force.push_back(std::log(std::max(el, eq)));
    log_energy.push_back(std::log(eJ));
  }
  const double force_rate = -least_squares_slope(log_n, log_force);
  const double energy_rate = -least_squares_slope(log_n, log_energy);
  std::printf("observed rates (least squares over n): forces %.2f, dual energy J %.2f\n", force_rate, energy_rate);
  EXPECT_GE(force_rate, 0.8);
  EXPECT_GE(energy_rate, 1.7);
  EXPECT_LT(log_force.back(), log_force.front() - std::log(8.0));
  EXPECT_LT(log_energy.back(), log_energy.front() - std::log(100.0));
}

TEST(FrictionPolygon, RegularPolygonConvergesToDisc) {
  const std::vector<int> sides = {8, 16, 32, 64, 128};
  std::vector<FrictionLaw> polygons;
  for (const int n : sides) polygons.push_back(FrictionLaw::regular_polygon(0.3, n));
  expect_polygon_convergence(FrictionLaw::disc(0.3), polygons, sides);
}

TEST(FrictionPolygon, EllipsePolygonConvergesToEllipse) {
  const std::vector<int> sides = {8, 16, 32, 64, 128};
  std::vector<FrictionLaw> polygons;
  for (const int n : sides) polygons.push_back(FrictionLaw::ellipse_polygon(0.2, 0.4, n));
  expect_polygon_convergence(FrictionLaw::ellipse(0.2, 0.4), polygons, sides);
}

}  // namespace
}  // namespace frictopt::study::validation
