// SPDX-License-Identifier: MIT
// Tresca dual QP: KKT conditions on random SPD problems for every law, an independent oracle
// (projected Gauss–Seidel), warm starts, split vs joint, a hand-computed 1-DOF case.
#include "frictopt/contact/tresca_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "contact/contact_test_problems.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::contact {
namespace {

using testing::kSeed;

TEST(TrescaSolverOptions, ValidateNamesFieldValueAndExpectation) {
  TrescaSolver::Options o;
  EXPECT_NO_THROW(o.validate());
  o.step_length_factor = 2.5;
  try {
    o.validate();
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("step_length_factor = 2.5; expected a value in (0, 2]"),
              std::string::npos)
        << e.what();
  }
  o = {};
  o.max_iterations = 0;
  EXPECT_THROW(o.validate(), InvalidInput);
  EXPECT_EQ(parse_tresca_algorithm(to_string(TrescaAlgorithm::kSplit)), TrescaAlgorithm::kSplit);
}

// A one-node dual QP solvable by hand (docs/theory/state-problem.md §5): stiffness k, load −L,
// gap g; contact iff L > kg, λ = L − kg. Tangentially stiffness k_t and load F = 1: the stick force
// would be F = 1 > s = 0.6, so the node slips in +e₁ with q = s·μ₊-end and u_t = (F − s)/k_t.
TEST(TrescaSolver, OneNodeSanityCaseMatchesHandComputation) {
  const double k = 2.0, big_l = 3.0, gap = 0.5, k_t = 1.0, force = 1.0, s = 0.6;
  Eigen::MatrixXd m(2, 2);
  m << 1.0 / k_t, 0.0, 0.0, 1.0 / k;
  const linalg::DenseOperator op(m);
  const TrescaSolver solver(op, FrictionLaw::interval(1.0, 1.0));
  Eigen::VectorXd c(2);
  c << -force / k_t, -big_l / k + gap;
  ContactState state;
  const auto summary = solver.solve(c, Eigen::VectorXd::Constant(1, s), state);
  ASSERT_TRUE(summary.converged()) << summary.brief_report();
  // Tolerance: the solution of a 2×2 diagonal QP is reached in one or two steps, exact to
  // rounding (a few ulps of the data of order 1).
  EXPECT_NEAR(state.lambda(0), big_l - k * gap, 1e-14);
  EXPECT_NEAR(state.q(0).x(), s, 1e-14);
  EXPECT_NEAR(state.u_t(0).x(), (force - s) / k_t, 1e-14);
  EXPECT_NEAR(state.normal_gap(0), 0.0, 1e-14);
  EXPECT_TRUE(state.is_slip(0));
  EXPECT_EQ(state.nodes[0].faces.slip, (FaceLocation{FrictionFace::kVertex, 1}));
  // Lifted: L < kg gives λ = 0 and the gap g − L/k stays open.
  c(1) = -0.5 / k + gap;
  const auto lifted = solver.solve(c, Eigen::VectorXd::Constant(1, s), state);
  ASSERT_TRUE(lifted.converged());
  EXPECT_EQ(state.lambda(0), 0.0);
  EXPECT_NEAR(state.normal_gap(0), gap - 0.5 / k, 1e-14);
  EXPECT_TRUE(state.is_separated(0));
}

struct RandomCase {
  std::string name;
  FrictionLaw law;
  Eigen::Index nodes;
};

std::vector<RandomCase> random_cases() {
  std::vector<RandomCase> cases;
  const std::vector<std::pair<std::string, FrictionLaw>> laws = {
      {"Interval", FrictionLaw::interval(0.3, 0.5)},
      {"Disc", FrictionLaw::disc(0.4)},
      {"Polygon8", FrictionLaw::regular_polygon(0.4, 8)},
      {"Anisotropic4", FrictionLaw::polygon({0.3, 0.6, 0.3, 0.6})},
      {"Ellipse", FrictionLaw::ellipse(0.2, 0.6)},
      {"EllipsePolygon16", FrictionLaw::ellipse_polygon(0.2, 0.6, 16)}};
  for (const auto& [name, law] : laws)
    for (Eigen::Index p : {5, 20, 60})
      cases.push_back({"Dim" + std::to_string(law.dim()) + "_" + name + "_" + std::to_string(p), law, p});
  return cases;
}

void PrintTo(const RandomCase& c, std::ostream* os) { *os << c.name; }

class TrescaRandom : public ::testing::TestWithParam<RandomCase> {};

// Tolerances: the solver stops at ‖g̃‖ <= 1e-10‖c‖; with M's condition number ≈ 9 the forces are
// accurate to ~1e-9 relative, so the dimensionless KKT residual and gap must be <= 1e-8 (the
// acceptance bound for the residuals of docs/contact.md §3). The PGS oracle is converged to 1e-15
// relative changes; the objective error of both is second order in the force error, so objectives
// agree to 1e-10 relative (plus 1e-12 absolute for objectives near 0).
TEST_P(TrescaRandom, SatisfiesKktAndMatchesProjectedGaussSeidel) {
  const auto& param = GetParam();
  std::mt19937_64 rng{kSeed + static_cast<std::uint64_t>(param.nodes)};
  const int dim = param.law.dim();
  const Eigen::MatrixXd m = testing::random_spd(dim * param.nodes, rng);
  const Eigen::VectorXd c = testing::random_c(dim, param.nodes, rng);
  std::uniform_real_distribution<double> uni(0.5, 1.5);
  Eigen::VectorXd s(param.nodes);
  for (auto& x : s) x = uni(rng);
  const linalg::DenseOperator op(m);
  for (auto algorithm : {TrescaAlgorithm::kJointMpgp, TrescaAlgorithm::kSplit}) {
    TrescaSolver::Options options;
    options.algorithm = algorithm;
    const TrescaSolver solver(op, std::vector<FrictionLaw>{param.law}, options);
    ContactState state;
    const auto summary = solver.solve(c, s, state);
    SCOPED_TRACE(summary.brief_report() + " seed " + std::to_string(kSeed));
    ASSERT_TRUE(summary.converged());
    // The random data must exercise every status, or the test proves little.
    int count[3] = {0, 0, 0};
    for (Eigen::Index i = 0; i < param.nodes; ++i) ++count[static_cast<int>(state.nodes[i].status)];
    if (param.nodes >= 20) {
      EXPECT_TRUE(count[0] > 0 && count[1] > 0 && count[2] > 0)
          << count[0] << " separated, " << count[1] << " stick, " << count[2] << " slip";
    }
    ::testing::Test::RecordProperty("report", summary.brief_report());
    EXPECT_LE(summary.relative_projected_gradient, options.relative_tolerance);
    EXPECT_LE(summary.kkt_residual, 1e-8);
    EXPECT_LE(summary.complementarity_gap, 1e-8);
    EXPECT_NEAR(summary.objective, testing::objective(m, c, state.z), 1e-12 * std::abs(summary.objective));
    // Independent check of feasibility, straight from the definitions.
    for (Eigen::Index i = 0; i < param.nodes; ++i) {
      EXPECT_GE(state.lambda(i), 0.0);
      EXPECT_LE(param.law.boundary_offset(state.q(i), s(i)), 1e-14);
      EXPECT_GE(state.normal_gap(i), -1e-8 * c.cwiseAbs().maxCoeff());
    }
    if (param.nodes <= 20) {
      const Eigen::VectorXd z_ref = testing::projected_gauss_seidel(m, c, s, {param.law}, dim);
      const double f_ref = testing::objective(m, c, z_ref);
      EXPECT_NEAR(summary.objective, f_ref, 1e-10 * std::abs(f_ref) + 1e-12);
      // M is SPD, so the minimizer is unique: forces agree to the solver's accuracy.
      EXPECT_LE((state.z - z_ref).norm(), 1e-7 * z_ref.norm());
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllLaws, TrescaRandom, ::testing::ValuesIn(random_cases()),
                         [](const auto& test_info) { return test_info.param.name; });

TEST(TrescaSolver, WarmStartReducesIterations) {
  std::mt19937_64 rng{kSeed + 7};
  const Eigen::Index p = 60;
  const Eigen::MatrixXd m = testing::random_spd(3 * p, rng);
  const Eigen::VectorXd c = testing::random_c(3, p, rng);
  const linalg::DenseOperator op(m);
  const TrescaSolver solver(op, FrictionLaw::regular_polygon(0.4, 8));
  const Eigen::VectorXd s = Eigen::VectorXd::Ones(p);
  ContactState warm;
  ASSERT_TRUE(solver.solve(c, s, warm).converged());
  // A nearby problem (1% change of the slip bounds, as between fixed-point iterations).
  const Eigen::VectorXd s2 = 1.01 * s;
  ContactState cold;
  const auto cold_summary = solver.solve(c, s2, cold);
  const auto warm_summary = solver.solve(c, s2, warm);
  ASSERT_TRUE(cold_summary.converged() && warm_summary.converged());
  EXPECT_LT(warm_summary.iterations, cold_summary.iterations)
      << "cold: " << cold_summary.brief_report() << "\nwarm: " << warm_summary.brief_report();
  EXPECT_LE((warm.z - cold.z).norm(), 1e-7 * cold.z.norm());
}

TEST(TrescaSolver, TrivialProblemsConvergeImmediately) {
  std::mt19937_64 rng{kSeed + 8};
  const Eigen::Index p = 10;
  const linalg::DenseOperator op(testing::random_spd(3 * p, rng));
  const TrescaSolver solver(op, FrictionLaw::disc(0.3));
  ContactState state;
  const auto zero = solver.solve(Eigen::VectorXd::Zero(3 * p), Eigen::VectorXd::Ones(p), state);
  EXPECT_TRUE(zero.converged());
  EXPECT_EQ(state.z, Eigen::VectorXd::Zero(3 * p));
  // Every node lifted and no tangential load: z = 0 is optimal, all separated.
  Eigen::VectorXd c = Eigen::VectorXd::Zero(3 * p);
  for (Eigen::Index i = 0; i < p; ++i) c(3 * i + 2) = 1.0;
  const auto lifted = solver.solve(c, Eigen::VectorXd::Ones(p), state);
  EXPECT_TRUE(lifted.converged());
  EXPECT_EQ(lifted.iterations, 0);
  for (Eigen::Index i = 0; i < p; ++i) EXPECT_TRUE(state.is_separated(i));
}

TEST(TrescaSolver, IterationLimitIsAStatusNotAnException) {
  std::mt19937_64 rng{kSeed + 9};
  const Eigen::Index p = 30;
  const linalg::DenseOperator op(testing::random_spd(3 * p, rng));
  TrescaSolver::Options options;
  options.max_iterations = 2;
  const TrescaSolver solver(op, FrictionLaw::disc(0.3), options);
  ContactState state;
  const auto summary = solver.solve(testing::random_c(3, p, rng), Eigen::VectorXd::Ones(p), state);
  EXPECT_EQ(summary.status, Status::kMaxIterations);
  EXPECT_GT(summary.kkt_residual, 0.0);
  EXPECT_THROW((void)solver.solve(Eigen::VectorXd::Zero(5), Eigen::VectorXd::Ones(p), state),
               InvalidInput);
  Eigen::VectorXd bad = Eigen::VectorXd::Ones(p);
  bad(3) = -1.0;
  EXPECT_THROW((void)solver.solve(Eigen::VectorXd::Zero(3 * p), bad, state), InvalidInput);
}

}  // namespace
}  // namespace frictopt::contact
