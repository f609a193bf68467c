// SPDX-License-Identifier: MIT
// Cattaneo–Mindlin in 3D through a loading program (issue 12, item 5; slow binary): a paraboloid
// pressed without friction, then dragged in steps. Stick radius against c = a·(1 − Q/μP)^{1/3},
// a = Hertz radius of the measured P. Two estimators of c: (i) the second moment of the stick
// deficit d_i = μλ_i − |q_i| (Mindlin: μp − |τ| = (μp0/a)·√(c² − r²) inside the stick disc and 0
// outside, a semi-elliptic distribution on radius c, so c² = (5/2)·Σd_i r_i²/Σd_i, the
// estimator of the Hertz radius), (ii) √(A_stick/π) from the stick nodes' tributary areas (the
// summary's stick_equivalent_radius). Tolerance 5% on the finest mesh (issue 12).
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
  std::printf("| mesh | step | drag [mm] | Q/(μP) | a Hertz [m] | c theory [m] | c moment [m] | err | c area [m] | err | stick/slip | time [s] |\n");
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
    def.dirichlet = {{"top", {2}, Eigen::Vector3d(0.0, 0.0, -0.012)}, {"top", {0, 1}, Eigen::Vector3d(0.001, 0.0, 0.0)}};
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
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf("| %d graded | %d | %.1f | %.3f | %.4f | %.4f | %.4f | %+.1f%% | %.4f | %+.1f%% | %d/%d | %.1f |\n", cells,
                  step.step, 1.0 * (step.step - 1), ratio, a, c_theory, c_moment, 100 * (c_moment / c_theory - 1), c_area,
                  100 * (c_area / c_theory - 1), res.num_stick, res.num_slip, seconds);
      EXPECT_LT(ratio, 1.0);
      if (cells == 32) {
        EXPECT_LE(validation::rel(c_moment, c_theory), 0.05);
      }
    });
    ASSERT_EQ(summary.status, Status::kConverged) << summary.brief_report();
    EXPECT_EQ(summary.factorizations, 1);
  }
}

}  // namespace
}  // namespace frictopt::study
