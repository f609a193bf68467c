// SPDX-License-Identifier: MIT
// FCLIB export: the file read back by fclib's own reader holds our W, q, μ; our Coulomb solution
// solves the exported problem in FCLIB's terms (fclib's merit function and the natural map);
// non-isotropic laws and stale states are rejected; `frictopt export-fclib` writes a readable file.
#include "frictopt/io/fclib_export.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <string>

extern "C" {
#include <fclib.h>
}

#include "common/temporary_directory.hpp"
#ifdef FRICTOPT_BINARY
#include "common/cli_runner.hpp"
#endif
#include "frictopt/contact/delassus.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"

namespace {

namespace fs = std::filesystem;
using frictopt::InvalidInput;
using frictopt::contact::FrictionLaw;
using frictopt::io::FclibExportOptions;
using frictopt::io::FclibLocalProblem;
using frictopt::study::BodyDefinition;
using frictopt::study::BodyState;
using frictopt::study::ElasticBody;

const fs::path kData = fs::path(FRICTOPT_SOURCE_DIR) / "tests/io/data";

BodyDefinition definition_of(const std::string& file) {
  return frictopt::io::load_case(kData / file).body;
}

// Each test writes into its own directory (named after the test and the process id, removed
// after the test), so parallel and repeated runs never share a file.
class FclibTest : public frictopt::testing::TemporaryDirectoryTest {
 protected:
  fs::path temp_file(const std::string& name) const { return dir_ / name; }
};

// RAII owners of what fclib's readers allocate (fclib_delete_local leaves the struct itself).
struct LocalDeleter {
  void operator()(fclib_local* p) const {
    fclib_delete_local(p);
    std::free(p);
  }
};
using LocalPtr = std::unique_ptr<fclib_local, LocalDeleter>;
struct SolutionDeleter {
  int count = 1;
  void operator()(fclib_solution* s) const { fclib_delete_solutions(s, count); }
};
using SolutionPtr = std::unique_ptr<fclib_solution, SolutionDeleter>;

LocalPtr read_local(const fs::path& path) { return LocalPtr(fclib_read_local(path.c_str())); }

// W from fclib's struct, whatever its storage (triplet, compressed column or row).
Eigen::MatrixXd dense(const fclib_matrix& a) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(a.m, a.n);
  if (a.nz >= 0) {
    for (int k = 0; k < a.nz; ++k) out(a.p[k], a.i[k]) += a.x[k];
  } else if (a.nz == -1) {
    for (int j = 0; j < a.n; ++j)
      for (int k = a.p[j]; k < a.p[j + 1]; ++k) out(a.i[k], j) += a.x[k];
  } else {
    for (int r = 0; r < a.m; ++r)
      for (int k = a.p[r]; k < a.p[r + 1]; ++k) out(r, a.i[k]) += a.x[k];
  }
  return out;
}

Eigen::Map<const Eigen::VectorXd> vec(const double* x, Eigen::Index n) { return {x, n}; }

// The isotropic 3D case with stick and slip nodes, solved once for all tests of the suite.
class FclibExport3d : public FclibTest {
 protected:
  static void SetUpTestSuite() {
    body_ = new ElasticBody(definition_of("fclib3d.toml"));
    state_ = new BodyState(body_->solve(body_->definition().initial_design, "initial design"));
  }
  static void TearDownTestSuite() {
    delete state_;
    delete body_;
  }
  static ElasticBody* body_;
  static BodyState* state_;
};
ElasticBody* FclibExport3d::body_ = nullptr;
BodyState* FclibExport3d::state_ = nullptr;

TEST_F(FclibExport3d, TheCaseHasStickAndSlipNodes) {
  ASSERT_TRUE(state_->contact);
  const auto& c = *state_->contact;
  ASSERT_TRUE(c.summary.converged()) << c.summary.brief_report();
  int stick = 0, slip = 0;
  for (Eigen::Index i = 0; i < c.state.num_nodes(); ++i) {
    stick += c.state.is_stick(i);
    slip += c.state.is_slip(i);
  }
  std::printf("fclib3d: %d contact nodes, %d stick, %d slip; %s\n",
              static_cast<int>(c.state.num_nodes()), stick, slip, c.summary.brief_report().c_str());
  EXPECT_GT(stick, 0);
  EXPECT_GT(slip, 0);
}

TEST_F(FclibExport3d, FileReadByFclibHoldsOurWqMu) {
  const fs::path path = temp_file("roundtrip.hdf5");
  FclibExportOptions options;
  options.case_name = "fclib3d.toml";
  const FclibLocalProblem problem =
      frictopt::io::export_fclib_local(path, *body_, *state_, options);
  const LocalPtr local = read_local(path);
  ASSERT_NE(local, nullptr);
  ASSERT_EQ(local->spacedim, 3);
  const Eigen::Index m = problem.W.rows();
  ASSERT_EQ(m, 3 * body_->contact_boundary()->num_nodes());
  ASSERT_EQ(local->W->m, m);
  ASSERT_EQ(local->W->n, m);
  EXPECT_EQ(local->V, nullptr);
  // HDF5 stores the doubles as they are: the round trip is exact.
  EXPECT_EQ((dense(*local->W) - problem.W).lpNorm<Eigen::Infinity>(), 0.0);
  EXPECT_EQ((vec(local->q, m) - problem.q).lpNorm<Eigen::Infinity>(), 0.0);
  EXPECT_EQ((vec(local->mu, m / 3).array() - 0.3).abs().maxCoeff(), 0.0);
  ASSERT_NE(local->info, nullptr);
  EXPECT_NE(std::string(local->info->description).find("fclib3d.toml"), std::string::npos);
  EXPECT_NE(std::string(local->info->title).find("frictopt"), std::string::npos);
}

TEST_F(FclibExport3d, WAndQAreOursUnderTheSignedPermutation) {
  // Independent route: P as an explicit matrix (per node rows (n, t1, t2) ← ours (q1, q2, λ)
  // with r_T = −q), W = P M Pᵀ and q = P c, from a fresh dense Delassus.
  const auto& boundary = *body_->contact_boundary();
  const auto& chol = body_->elasticity().factorization();
  const Eigen::MatrixXd M = frictopt::contact::dense_delassus(chol, boundary);
  Eigen::VectorXd c = boundary.times(chol.solve(body_->elasticity().load()));
  const Eigen::Index p = boundary.num_nodes();
  for (Eigen::Index i = 0; i < p; ++i) c(3 * i + 2) += state_->contact->gaps(i);
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(3 * p, 3 * p);
  for (Eigen::Index i = 0; i < p; ++i) {
    P(3 * i, 3 * i + 2) = 1.0;
    P(3 * i + 1, 3 * i) = -1.0;
    P(3 * i + 2, 3 * i + 1) = -1.0;
  }
  FclibExportOptions si;
  si.normalize_units = false;
  const FclibLocalProblem problem = frictopt::io::make_fclib_local(*body_, *state_, si);
  // Both sides are the same products of the same numbers up to the order of summation in the
  // dense solves: 1e-12 relative.
  EXPECT_LE((problem.W - P * M * P.transpose()).norm(), 1e-12 * M.norm());
  EXPECT_LE((problem.q - P * c).norm(), 1e-12 * c.norm());
  EXPECT_LE((problem.W - problem.W.transpose()).norm(), 1e-14 * M.norm());

  // Physical reading: u = W r + q is (gap after deformation, tangential displacement) and
  // r = (λ, τ) with τ = −q the force on the body, node by node.
  const auto& s = state_->contact->state;
  double u_scale = 0.0, r_scale = 0.0, u_err = 0.0, r_err = 0.0;
  for (Eigen::Index i = 0; i < p; ++i) {
    const Eigen::Vector3d u_expected(s.normal_gap(i), s.u_t(i).x(), s.u_t(i).y());
    const Eigen::Vector3d r_expected(s.lambda(i), -s.q(i).x(), -s.q(i).y());
    u_err = std::max(u_err, (problem.u.segment<3>(3 * i) - u_expected).lpNorm<Eigen::Infinity>());
    r_err = std::max(r_err, (problem.r.segment<3>(3 * i) - r_expected).lpNorm<Eigen::Infinity>());
    u_scale = std::max(u_scale, u_expected.lpNorm<Eigen::Infinity>());
    r_scale = std::max(r_scale, r_expected.lpNorm<Eigen::Infinity>());
  }
  EXPECT_EQ(r_err, 0.0);              // a pure relabelling
  EXPECT_LE(u_err, 1e-10 * u_scale);  // Mz + c recomputed with the same M: round-off
  EXPECT_GT(r_scale, 0.0);
}

TEST_F(FclibExport3d, OurSolutionSolvesTheExportedProblemByFclibsMerit) {
  const fs::path path = temp_file("merit.hdf5");
  FclibExportOptions options;
  options.normalize_units = true;  // so that fclib's absolute natural map reads as relative
  const FclibLocalProblem problem =
      frictopt::io::export_fclib_local(path, *body_, *state_, options);
  ASSERT_TRUE(problem.solution_is_exact);
  const LocalPtr local = read_local(path);
  ASSERT_NE(local, nullptr);
  const SolutionPtr solution(fclib_read_solution(path.c_str()), SolutionDeleter{1});
  ASSERT_NE(solution, nullptr);
  const double merit = fclib_merit_local(local.get(), MERIT_1, solution.get());
  const double natural = frictopt::io::fclib_natural_map_residual(problem, problem.r);
  std::printf(
      "fclib3d: fclib_merit_local (normalized units) = %.3e, natural-map residual = %.3e, "
      "units F = %.6e N, L = %.6e m, solver KKT residual %.3e\n",
      merit, natural, problem.force_unit, problem.length_unit,
      state_->contact->summary.kkt_residual);
  // The Coulomb solver stops at a relative fixed-point increment of 1e-10 and inner QPs of
  // relative KKT residual ~1e-10 (its defaults); both measures are relative at these units.
  EXPECT_LE(merit, 1e-8);
  EXPECT_LE(natural, 1e-8);

  // The measures see a wrong mapping: r_T with the opposite sign (τ = +q) is far from a solution.
  fclib_solution flipped = *solution;
  Eigen::VectorXd r_wrong = vec(solution->r, problem.r.size());
  for (Eigen::Index i = 0; i < problem.num_contacts(); ++i) r_wrong.segment<2>(3 * i + 1) *= -1.0;
  Eigen::VectorXd u_wrong = problem.W * r_wrong + problem.q;
  flipped.r = r_wrong.data();
  flipped.u = u_wrong.data();
  EXPECT_GT(fclib_merit_local(local.get(), MERIT_1, &flipped), 1e-3);
  EXPECT_GT(frictopt::io::fclib_natural_map_residual(problem, r_wrong), 1e-3);
}

TEST_F(FclibExport3d, SiUnitsAndNormalizedUnitsDescribeTheSameProblem) {
  FclibExportOptions si_units;
  si_units.normalize_units = false;
  const FclibLocalProblem si = frictopt::io::make_fclib_local(*body_, *state_, si_units);
  FclibExportOptions normalized;  // the default (SI units broke other solvers' settings)
  EXPECT_TRUE(normalized.normalize_units);
  EXPECT_NE(frictopt::io::make_fclib_local(*body_, *state_, normalized).description.find("Units: normalized"),
            std::string::npos);
  const FclibLocalProblem scaled = frictopt::io::make_fclib_local(*body_, *state_, normalized);
  EXPECT_EQ(si.force_unit, 1.0);
  EXPECT_EQ(scaled.r.lpNorm<Eigen::Infinity>(), 1.0);
  EXPECT_LE((scaled.W * scaled.length_unit / scaled.force_unit - si.W).norm(), 1e-14 * si.W.norm());
  EXPECT_LE((scaled.u * scaled.length_unit - si.u).norm(), 1e-12 * si.u.norm());
  EXPECT_NEAR(frictopt::io::fclib_natural_map_residual(si, si.r),
              frictopt::io::fclib_natural_map_residual(scaled, scaled.r), 1e-12);
}

TEST_F(FclibExport3d, RejectsAStateThatIsNotTheBodysLastSolve) {
  ElasticBody other(definition_of("fclib3d.toml"));
  const BodyState first = other.solve(other.definition().initial_design, "first");
  const Eigen::VectorXd lower = 0.5 * other.definition().initial_design;
  const BodyState second = other.solve(lower, "second");
  EXPECT_NO_THROW(static_cast<void>(frictopt::io::make_fclib_local(other, second)));
  try {
    static_cast<void>(frictopt::io::make_fclib_local(other, first));
    ADD_FAILURE() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("most recent solve"), std::string::npos) << e.what();
  }
}

using FclibExport = FclibTest;

std::string export_error(FrictionLaw law) {
  BodyDefinition def = definition_of("fclib3d.toml");
  def.contact->law = std::move(law);
  ElasticBody body(def);
  const BodyState state = body.solve(def.initial_design);
  try {
    static_cast<void>(frictopt::io::make_fclib_local(body, state));
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "no exception";
}

TEST_F(FclibExport, RejectsAnisotropicLawsNamingTheKind) {
  const std::string polygon = export_error(FrictionLaw::polygon({0.3, 0.5, 0.3, 0.5}));
  EXPECT_NE(polygon.find("contact.friction.kind = polygon"), std::string::npos) << polygon;
  EXPECT_NE(polygon.find("isotropic Coulomb cones"), std::string::npos) << polygon;
  EXPECT_NE(polygon.find("disc_exact"), std::string::npos) << polygon;
  const std::string ellipse = export_error(FrictionLaw::ellipse(0.4, 0.2));
  EXPECT_NE(ellipse.find("contact.friction.kind = ellipse_exact"), std::string::npos) << ellipse;
  const std::string ellipse_gon = export_error(FrictionLaw::ellipse_polygon(0.4, 0.2, 8));
  EXPECT_NE(ellipse_gon.find("contact.friction.kind = ellipse "), std::string::npos) << ellipse_gon;
}

TEST_F(FclibExport, RegularPolygonIsExportedAsTheDiscWithTheSolutionAsAGuess) {
  BodyDefinition def = definition_of("fclib3d.toml");
  def.contact->law = FrictionLaw::regular_polygon(0.3, 16);
  ElasticBody body(def);
  const BodyState state = body.solve(def.initial_design);
  const fs::path path = temp_file("isotropic.hdf5");
  const FclibLocalProblem problem = frictopt::io::export_fclib_local(path, body, state);
  EXPECT_FALSE(problem.solution_is_exact);
  EXPECT_NE(problem.description.find("regular 16-gon"), std::string::npos) << problem.description;
  const LocalPtr local = read_local(path);
  ASSERT_NE(local, nullptr);
  // μ is the n-gon's vertex radius: the case's 0.3 up to the rounding of cos, sin and the norm.
  EXPECT_NEAR(local->mu[0], 0.3, 4 * std::numeric_limits<double>::epsilon());
  int count = 0;
  fclib_solution* guesses = fclib_read_guesses(path.c_str(), &count);
  ASSERT_EQ(count, 1);
  const SolutionPtr owner(guesses, SolutionDeleter{count});
  EXPECT_EQ((vec(guesses->r, problem.r.size()) - problem.r).lpNorm<Eigen::Infinity>(), 0.0);
  // The 16-gon solution is close to, not exactly, the disc solution: its natural-map residual
  // in the disc problem is of the order of the polygon's deviation from the disc, at most
  // 1 − cos(π/16) ≈ 1.9% (last measured 6.4e-3), and far above the solver's round-off and
  // tolerances (~1e-10): bounded on both sides so an exact disc solve or a wrong map both fail.
  const double natural = frictopt::io::fclib_natural_map_residual(problem, problem.r);
  std::printf("16-gon solution in the disc problem: natural-map residual %.3e\n", natural);
  EXPECT_GT(natural, 1e-5);
  EXPECT_LT(natural, 2e-2);
}

TEST_F(FclibExport, Exports2dProblemsWithSpacedim2) {
  ElasticBody body(definition_of("fclib2d.toml"));
  const BodyState state = body.solve(body.definition().initial_design);
  ASSERT_TRUE(state.contact && state.contact->summary.converged());
  ASSERT_GT(state.contact->state.normal_forces().maxCoeff(), 0.0) << "the 2D case should touch";
  const fs::path path = temp_file("plane.hdf5");
  const FclibLocalProblem problem = frictopt::io::export_fclib_local(path, body, state);
  const LocalPtr local = read_local(path);
  ASSERT_NE(local, nullptr);
  EXPECT_EQ(local->spacedim, 2);
  EXPECT_EQ((dense(*local->W) - problem.W).lpNorm<Eigen::Infinity>(), 0.0);
  // fclib's merit function is 3D only; the natural map in FCLIB's variables is ours.
  const double natural = frictopt::io::fclib_natural_map_residual(problem, problem.r);
  std::printf("fclib2d: natural-map residual %.3e\n", natural);
  EXPECT_LE(natural, 1e-8);
}

TEST_F(FclibExport, RejectsABodyWithoutFoundation) {
  BodyDefinition def = definition_of("fclib3d.toml");
  def.contact.reset();
  ElasticBody body(def);
  const BodyState state = body.solve(def.initial_design);
  EXPECT_THROW(static_cast<void>(frictopt::io::make_fclib_local(body, state)), InvalidInput);
}

#ifdef FRICTOPT_BINARY
using FclibExportCli = FclibTest;

TEST_F(FclibExportCli, WritesAFileFclibReads) {
  const fs::path out = temp_file("cli.hdf5");
  const frictopt::testing::RunResult run =
      frictopt::testing::run_frictopt("export-fclib " + (kData / "small3d_disc.toml").string() + " " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const LocalPtr local = read_local(out);
  ASSERT_NE(local, nullptr);
  EXPECT_EQ(local->spacedim, 3);
  // 7 × 6 bottom nodes minus the 6 on the clamped left face.
  EXPECT_EQ(local->W->m, 3 * (7 * 6 - 6));
  EXPECT_EQ(local->mu[0], 0.3);
  EXPECT_NE(std::string(local->info->description).find("small3d_disc.toml"), std::string::npos);
  const SolutionPtr solution(fclib_read_solution(out.c_str()), SolutionDeleter{1});
  ASSERT_NE(solution, nullptr);

  // A polygon law is refused with the explanation and exit code 2 (invalid input).
  const fs::path polygon_case = temp_file("polygon.toml");
  {
    std::string toml = frictopt::testing::read_text(kData / "small3d_disc.toml");
    const std::string disc = "kind = \"disc_exact\"\nmu = 0.3";
    const std::size_t at = toml.find(disc);
    ASSERT_NE(at, std::string::npos) << "small3d_disc.toml no longer holds '" << disc << "'";
    toml.replace(at, disc.size(), "kind = \"polygon\"\nmu_vertices = [0.3, 0.5, 0.3, 0.5]");
    std::ofstream(polygon_case) << toml;
  }
  const frictopt::testing::RunResult bad = frictopt::testing::run_frictopt(
      "export-fclib " + polygon_case.string() + " " + temp_file("polygon.hdf5").string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("isotropic Coulomb cones"), std::string::npos) << bad.output;
  // The refusal comes before the solve (no solver report is printed).
  EXPECT_EQ(bad.output.find("Coulomb fixed point"), std::string::npos) << bad.output;
  EXPECT_EQ(bad.output.find("iterations"), std::string::npos) << bad.output;
}

TEST_F(FclibExportCli, NormalizedUnitsAreTheDefaultAndSiIsAnOption) {
  const fs::path normalized = temp_file("normalized.hdf5"), si = temp_file("si.hdf5");
  const auto a = frictopt::testing::run_frictopt("export-fclib " + (kData / "fclib3d.toml").string() + " " +
                                                 normalized.string());
  ASSERT_EQ(a.exit_code, 0) << a.output;
  const auto b = frictopt::testing::run_frictopt("export-fclib " + (kData / "fclib3d.toml").string() + " " +
                                                 si.string() + " --units si");
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const LocalPtr n = read_local(normalized), s = read_local(si);
  ASSERT_NE(n, nullptr);
  ASSERT_NE(s, nullptr);
  EXPECT_NE(std::string(n->info->description).find("Units: normalized"), std::string::npos);
  EXPECT_NE(std::string(s->info->description).find("Units: SI"), std::string::npos);
  // In normalized units our reactions r have max norm 1; in SI they are forces in N.
  const SolutionPtr rn(fclib_read_solution(normalized.c_str()), SolutionDeleter{1});
  ASSERT_NE(rn, nullptr);
  EXPECT_DOUBLE_EQ(vec(rn->r, n->W->m).lpNorm<Eigen::Infinity>(), 1.0);
}

TEST_F(FclibExportCli, ADeviceOrALinkAsTargetIsRefusedAndLeftAsItWas) {
  // As root, export-fclib CASE /dev/full replaced the device by a file.
  const auto dev = frictopt::testing::run_frictopt("export-fclib " + (kData / "small3d_disc.toml").string() +
                                                   " /dev/null");
  EXPECT_EQ(dev.exit_code, 2) << dev.output;
  EXPECT_NE(dev.output.find("character device"), std::string::npos) << dev.output;
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  const fs::path target = temp_file("target.txt"), link = temp_file("link.hdf5");
  std::ofstream(target) << "keep";
  fs::remove(link);
  fs::create_symlink(target, link);
  const auto linked = frictopt::testing::run_frictopt("export-fclib " + (kData / "small3d_disc.toml").string() + " " +
                                                      link.string());
  EXPECT_EQ(linked.exit_code, 2) << linked.output;
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(frictopt::testing::read_text(target), "keep");
}
#endif

}  // namespace
