// SPDX-License-Identifier: MIT
// Time of one direction-finding QP of bundle shape (n + 1 variables, m cuts) as n grows.
#include <benchmark/benchmark.h>

#include <random>

#include "frictopt/optim/dense_qp.hpp"

namespace fo = frictopt::optim;

static void BM_BundleShapedQp(benchmark::State& state) {
  const auto n = static_cast<Eigen::Index>(state.range(0));
  const Eigen::Index m = 2 * n;
  std::mt19937_64 rng{20261121};
  std::normal_distribution<double> normal;
  fo::QpProblem qp;
  qp.H = Eigen::MatrixXd::Zero(n + 1, n + 1);
  qp.H.topLeftCorner(n, n).setIdentity();
  qp.g = Eigen::VectorXd::Zero(n + 1);
  qp.g(n) = 1.0;
  qp.A_in.resize(m, n + 1);
  qp.b_in.resize(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) qp.A_in(i, j) = normal(rng);
    qp.A_in(i, n) = -1.0;
    qp.b_in(i) = std::abs(normal(rng));
  }
  qp.b_in(0) = 0.0;
  qp.A_eq.resize(0, n + 1);
  qp.b_eq.resize(0);
  Eigen::VectorXd start = Eigen::VectorXd::Zero(n + 1);
  const fo::DenseQpSolver solver;
  for (auto _ : state) {
    auto s = solver.solve(qp, start);
    benchmark::DoNotOptimize(s.objective);
  }
}
BENCHMARK(BM_BundleShapedQp)->Arg(5)->Arg(15)->Arg(50);
BENCHMARK_MAIN();
