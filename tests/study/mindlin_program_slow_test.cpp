// SPDX-License-Identifier: MIT
// Cattaneo–Mindlin in 3D through a loading program (docs/experiments.md §2; slow binary): a
// paraboloid pressed without friction, then dragged in steps. Stick radius against c = a·(1 −
// Q/μP)^{1/3}, a = Hertz radius of the measured P. Two estimators of c: (i) the second moment of
// the stick deficit d_i = μλ_i − |q_i| (Mindlin: μp − |τ| = (μp0/a)·√(c² − r²) inside the stick
// disc and 0 outside, a semi-elliptic distribution on radius c, so c² = (5/2)·Σd_i r_i²/Σd_i, the
// estimator of the Hertz radius), (ii) √(A_stick/π) from the stick nodes' tributary areas (the
// summary's stick_equivalent_radius). Tolerance 5% on the finest mesh.
//   ./build/tests/study/study_program_slow_test | grep '^|'
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "frictopt/study/loading_program.hpp"
#include "study/contact_validation.hpp"

namespace frictopt::study {
namespace {

using contact::FrictionLaw;

TEST(CattaneoMindlin3D, StickRadiusFromTheLoadingProgramMatchesTheory) {
  const double mu = 0.3;
  std::printf(
      "| mesh | step | drag [mm] | Q/(μP) | a Hertz [m] | c theory [m] | c moment [m] | err | c "
      "area [m] | err | stick/slip | time [s] |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const int cells : {24, 32}) {
    validation::BlockSpec s;
    s.cells = cells;
    s.layers = cells / 3;
    s.growth = 1.2;  // graded toward the contact zone (as the 3D Hertz study)
    s.refine_min = 0.3;
    s.refine_max = 0.7;
    s.law = FrictionLaw::disc(mu);
    s.top_displacement = Eigen::Vector3d(0.0, 0.0, -0.012);
    BodyDefinition def = validation::block_definition(s);
    def.dirichlet = {{"top", {2}, Eigen::Vector3d(0.0, 0.0, -0.012)},
                     {"top", {0, 1}, Eigen::Vector3d(0.001, 0.0, 0.0)}};
    LoadingProgramDefinition program;
    program.steps.push_back({"press", {}, {1.0, 0.0}, {}, false});
    for (double f : {1.0, 2.0, 3.0}) program.steps.push_back({"drag", {}, {1.0, f}, {}, true});
    ElasticBody body(def);
    LoadingProgram runner(body, program);
    const Eigen::VectorXd r = validation::apex_distances(body, s.width);
    const auto start = std::chrono::steady_clock::now();
    const auto summary = runner.run(def.initial_design, [&](const LoadStepResult& step) {
      ASSERT_EQ(step.state.summary.status, Status::kConverged) << step.state.summary.brief_report();
      if (step.step == 1) return;
      const contact::ContactState& st = step.state.contact->state;
      const contact::ContactResultants& res = step.state.contact->resultants;
      Eigen::VectorXd deficit(st.num_nodes());
      for (Eigen::Index i = 0; i < st.num_nodes(); ++i)
        deficit(i) = std::max(0.0, mu * st.lambda(i) - st.q(i).norm());
      const double ratio = res.tangential_force_norm / (mu * res.normal_force);
      const double a = validation::hertz(3, res.normal_force, s.radius, s.young, s.poisson).radius;
      const double c_theory = a * std::cbrt(1.0 - ratio);
      const double c_moment = validation::moment_radius(3, deficit, r);
      const double c_area = res.stick_equivalent_radius;
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf(
          "| %d graded | %d | %.1f | %.3f | %.4f | %.4f | %.4f | %+.1f%% | %.4f | %+.1f%% | %d/%d "
          "| %.1f |\n",
          cells, step.step, 1.0 * (step.step - 1), ratio, a, c_theory, c_moment,
          100 * (c_moment / c_theory - 1), c_area, 100 * (c_area / c_theory - 1), res.num_stick,
          res.num_slip, seconds);
      EXPECT_LT(ratio, 1.0);
      if (cells == 32) {
        EXPECT_LE(validation::rel(c_moment, c_theory), 0.05);
      }
    });
    ASSERT_EQ(summary.status, Status::kConverged) << summary.brief_report();
    EXPECT_EQ(summary.factorizations, 1);
  }
}

// Mindlin–Deresiewicz: the tangential displacement of the top cycles between ±d* after the
// frictionless press; the hysteresis loop's dissipated energy per cycle against theory.
// Theory (sphere on a rigid flat; Johnson, Contact Mechanics §7.4): the virgin curve
// δ₀(Q) = C[1 − (1 − Q/μP)^{2/3}], C = 3μP(2 − ν)/(16Ga), and Masing's rule for the branches,
// δ_load(Q) = −δ* + 2δ₀((Q + Q*)/2), δ_unload(Q) = δ* − 2δ₀((Q* − Q)/2); the energy per cycle is
// W = ∫_{−Q*}^{Q*} (δ_unload − δ_load) dQ, integrated by Simpson's rule (1000 intervals) with Q*
// the measured force amplitude. Measured: (i) the friction work Σ_steps Σ_i ⟨q_i, Δu_t^i⟩ over
// one cycle (exact in the incremental problem), (ii) the loop area ∮F dδ of the platen force
// against the platen displacement by the trapezoidal rule (the block's bulk shear is elastic and
// adds no area). Tolerance 10% (the rigid foundation couples normal and tangential tractions,
// Dundurs β ≠ 0, which the half-space theory ignores; 2D Cattaneo–Mindlin shows ≈ 5%).
TEST(MindlinDeresiewicz3D, HysteresisEnergyPerCycleMatchesTheory) {
  std::printf(
      "| mesh | P [N] | a [m] | Q*/(μP) | W theory [J] | W friction work [J] | err | W loop area "
      "[J] | err |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (const int cells : {16, 24, 32}) {
    SCOPED_TRACE("cells = " + std::to_string(cells));
    const double mu = 0.3;
    validation::BlockSpec s;
    s.cells = cells;
    s.layers = cells / 3;
    s.growth = 1.2;
    s.refine_min = 0.3;
    s.refine_max = 0.7;
    s.law = FrictionLaw::disc(mu);
    s.top_displacement = Eigen::Vector3d(0.0, 0.0, -0.012);
    BodyDefinition def = validation::block_definition(s);
    const double amplitude = 0.006;  // m: Q*/μP ≈ 0.7: a slip annulus of several cells
    def.dirichlet = {{"top", {2}, Eigen::Vector3d(0.0, 0.0, -0.012)},
                     {"top", {0, 1}, Eigen::Vector3d(amplitude, 0.0, 0.0)}};
    LoadingProgramDefinition program;
    program.steps.push_back({"press", {}, {1.0, 0.0}, {}, false});
    const int n = 6;  // steps per quarter of the cycle
    std::vector<double> drag;
    for (int k = 1; k <= n; ++k) drag.push_back(double(k) / n);             // 0 → +d*
    for (int k = 1; k <= 2 * n; ++k) drag.push_back(1.0 - double(k) / n);   // +d* → −d*
    for (int k = 1; k <= 2 * n; ++k) drag.push_back(-1.0 + double(k) / n);  // −d* → +d*
    for (double f : drag) program.steps.push_back({"drag", {}, {1.0, f}, {}, true});
    ElasticBody body(def);
    LoadingProgram runner(body, program);
    std::vector<double> force, displacement, work;
    double P = 0.0;
    const auto summary = runner.run(def.initial_design, [&](const LoadStepResult& r) {
      ASSERT_EQ(r.state.summary.status, Status::kConverged) << r.state.summary.brief_report();
      const contact::ContactState& st = r.state.contact->state;
      double w = 0.0;  // friction work of the step on the slip increment u_t − u_t^{k−1} = −∇_q
      for (Eigen::Index i = 0; i < st.num_nodes(); ++i) w += st.q(i).dot(st.u_t(i));
      force.push_back(-r.state.contact->resultants.tangential_force(0));  // the platen's pull
      displacement.push_back(r.step == 1 ? 0.0
                                         : amplitude * drag[static_cast<std::size_t>(r.step - 2)]);
      work.push_back(r.step == 1 ? 0.0 : w);
      P = r.state.contact->resultants.normal_force;
    });
    ASSERT_EQ(summary.status, Status::kConverged) << summary.brief_report();
    // The closed cycle: from index n (step n + 1, at +d*) through −d* back to +d* (the last step).
    const std::size_t first = n, last = force.size() - 1;
    ASSERT_EQ(last - first, 4u * n);
    double dissipated = 0.0, loop = 0.0;
    for (std::size_t k = first + 1; k <= last; ++k) {
      dissipated += work[k];
      loop += 0.5 * (force[k] + force[k - 1]) * (displacement[k] - displacement[k - 1]);
    }
    const double q_star = 0.5 * (force[first] - force[first + 2 * n]);  // half the force range
    const double a = validation::hertz(3, P, s.radius, s.young, s.poisson).radius;
    const double G = s.young / (2.0 * (1.0 + s.poisson));
    const double C = 3.0 * mu * P * (2.0 - s.poisson) / (16.0 * G * a);
    const auto virgin = [&](double q) {
      return C * (1.0 - std::pow(1.0 - q / (mu * P), 2.0 / 3.0));
    };
    const double delta_star = virgin(q_star);
    const int m = 1000;
    double theory = 0.0;
    for (int k = 0; k <= m; ++k) {
      const double q = -q_star + 2.0 * q_star * k / m;
      const double gap = (delta_star - 2.0 * virgin(0.5 * (q_star - q))) -
                         (-delta_star + 2.0 * virgin(0.5 * (q + q_star)));
      theory += (k == 0 || k == m ? 1.0 : (k % 2 ? 4.0 : 2.0)) * gap;
    }
    theory *= (2.0 * q_star / m) / 3.0;
    std::printf("| %d graded | %.4e | %.4f | %.3f | %.4e | %.4e | %+.1f%% | %.4e | %+.1f%% |\n",
                cells, P, a, q_star / (mu * P), theory, dissipated, 100 * (dissipated / theory - 1),
                loop, 100 * (loop / theory - 1));
    EXPECT_GT(dissipated, 0.0);
    if (cells == 32) {
      EXPECT_LE(validation::rel(dissipated, theory), 0.10);
    }
    // Energy balance of the discrete model: the loop area equals the friction work up to the
    // trapezoidal rule's error on 2n steps per branch.
    EXPECT_LE(validation::rel(loop, dissipated), 0.05);
  }
}

}  // namespace
}  // namespace frictopt::study
