// SPDX-License-Identifier: MIT
// Elasticity phases on 3D meshes of ~20k, ~100k and ~200k unknowns: assembly, symbolic
// analysis, numeric factorization and solve (linalg::SpdSolver, CHOLMOD supernodal), with peak memory and the
// ratio assembly / factorization (target <= 0.25 at the largest size).
//   build/bench/fem/elasticity_benchmark --benchmark_repetitions=3
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>
#include <vector>

#include "frictopt/fem/linear_elasticity.hpp"
#include "frictopt/mesh/structured_mesh.hpp"
#include "common/timing.hpp"

namespace {

using frictopt::bench::Clock;
using frictopt::bench::seconds;
using frictopt::bench::peak_rss_megabytes;

// A cube of n³ hexahedra with a curved Bézier bottom, clamped on the left face and pressed on top.
void BM_ElasticityPhases(benchmark::State& state) {
  using namespace frictopt;
  const int n = static_cast<int>(state.range(0));
  const bool contact_last = state.range(1) != 0;  // order the bottom (contact) DOFs last
  const auto surface = shape::BezierShape::surface(1.0, 1.0, 4, 4);
  const mesh::Mesh mesh = mesh::StructuredMesh(surface, 1.0, {{n, n, n}, 1.5}).take_mesh();
  Eigen::VectorXd alpha(16);
  for (int k = 0; k < 16; ++k) alpha(k) = 0.05 + 0.03 * std::sin(1.3 * k);
  const Eigen::MatrixXd X = mesh.positions(alpha);
  const fem::IsotropicMaterial steel{2.1e11, 0.3, fem::PlaneModel::kPlaneStrain};
  double assembly = 0, analysis = 0, factorization = 0, solve = 0;
  double factor_nnz = 0, factor_flops = 0;
  int unknowns = 0;
  for (auto _ : state) {
    fem::LinearElasticity problem(mesh, steel, fem::expand_dirichlet(mesh, {{"left", {}, {}}}),
                                  {{"top", Eigen::Vector3d(0, 0, -1e7)}});
    unknowns = problem.dofs().num_free();
    auto t0 = Clock::now();
    problem.assemble(X);
    auto t1 = Clock::now();
    const std::unique_ptr<linalg::SpdSolver> solver = linalg::SpdSolver::create();
    Status analyzed = Status::kNotRun;
    if (contact_last) {
      std::vector<int> trailing;
      for (int node : mesh.boundary("bottom").nodes)
        for (int c = 0; c < 3; ++c)
          if (problem.dofs().is_free(node * 3 + c)) trailing.push_back(problem.dofs().free_index(node * 3 + c));
      analyzed = solver->analyze(problem.stiffness(), trailing);
    } else {
      analyzed = solver->analyze(problem.stiffness());
    }
    auto t2 = Clock::now();
    if (analyzed != Status::kConverged || solver->factorize(problem.stiffness()) != Status::kConverged)
      state.SkipWithError("factorization failed");
    auto t3 = Clock::now();
    const Eigen::VectorXd u = solver->solve(problem.load());
    auto t4 = Clock::now();
    benchmark::DoNotOptimize(u.data());
    assembly += seconds(t0, t1);
    analysis += seconds(t1, t2);
    factorization += seconds(t2, t3);
    solve += seconds(t3, t4);
    factor_nnz = solver->factor_nonzeros();
    factor_flops = solver->factor_flops();
  }
  const double runs = static_cast<double>(state.iterations());
  state.counters["unknowns"] = unknowns;
  state.counters["assembly_s"] = assembly / runs;
  state.counters["analysis_s"] = analysis / runs;
  state.counters["factorization_s"] = factorization / runs;
  state.counters["solve_s"] = solve / runs;
  state.counters["assembly_over_factorization"] = assembly / factorization;
  state.counters["factor_nnz_M"] = factor_nnz / 1e6;
  state.counters["factor_Gflop"] = factor_flops / 1e9;
  state.counters["peak_rss_MB"] = peak_rss_megabytes();
}

// n = 18, 31, 40: 3·19³ ≈ 20.6k, 3·32³ ≈ 98k, 3·41³ ≈ 207k DOFs (minus the clamped face).
// Second argument 1: the bottom (contact) DOFs ordered last, as the contact solver does.
BENCHMARK(BM_ElasticityPhases)
    ->ArgsProduct({{18, 31, 40}, {0, 1}})
    ->ArgNames({"n", "contact_last"})
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
