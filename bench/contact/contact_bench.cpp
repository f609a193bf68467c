// SPDX-License-Identifier: MIT
// Tresca and Coulomb solves on dense Delassus-like operators with 100, 1000 and 2500 contact
// nodes (3D): iterations, operator applications and time, as Google Benchmark counters.
//
// Operator: M = K ⊗ B + δI, with K_ij = exp(−|x_i − x_j|/ℓ) the exponential kernel (strictly
// positive definite in any dimension) on a jittered square grid of spacing h, ℓ = 3h, B a fixed
// 3×3 SPD block with tangential–normal coupling, δ = 0.05. Like a Delassus operator its entries
// decay with distance and it is fully dense; it is SPD by construction (Kronecker product of
// SPD matrices plus a shift), so no factorization is needed to trust it. Load: nodes within
// 0.6 of the centre are pressed (c_ν < 0), the rest lifted; tangential loads random.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>

#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/contact/tresca_solver.hpp"

namespace {

using namespace frictopt::contact;

constexpr std::uint64_t kSeed = 20261121;

struct Problem {
  std::unique_ptr<frictopt::linalg::DenseOperator> op;
  Eigen::VectorXd c;
  Eigen::Index nodes = 0;
};

const Problem& problem(Eigen::Index side) {
  static std::map<Eigen::Index, Problem> cache;
  auto it = cache.find(side);
  if (it != cache.end()) return it->second;
  std::mt19937_64 rng{kSeed};
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::Index p = side * side;
  const double h = 2.0 / static_cast<double>(side), ell = 3.0 * h;
  Eigen::MatrixXd x(p, 2);
  for (Eigen::Index a = 0; a < side; ++a)
    for (Eigen::Index b = 0; b < side; ++b)
      x.row(a * side + b) << -1.0 + (static_cast<double>(a) + 0.5 + jitter(rng)) * h,
          -1.0 + (static_cast<double>(b) + 0.5 + jitter(rng)) * h;
  Eigen::Matrix3d block;
  block << 1.0, 0.0, 0.3, 0.0, 1.0, 0.2, 0.3, 0.2, 2.0;
  Eigen::MatrixXd m(3 * p, 3 * p);
  for (Eigen::Index j = 0; j < p; ++j)
    for (Eigen::Index i = 0; i < p; ++i)
      m.block<3, 3>(3 * i, 3 * j) = std::exp(-(x.row(i) - x.row(j)).norm() / ell) * block;
  m.diagonal().array() += 0.05;
  Problem pr;
  pr.op = std::make_unique<frictopt::linalg::DenseOperator>(std::move(m));
  pr.nodes = p;
  pr.c.resize(3 * p);
  for (Eigen::Index i = 0; i < p; ++i) {
    const double r = x.row(i).norm();
    pr.c(3 * i) = 0.3 * normal(rng);
    pr.c(3 * i + 1) = 0.3 * normal(rng);
    pr.c(3 * i + 2) = r < 0.6 ? -(1.0 - r) : 0.1 * r;
  }
  return cache.emplace(side, std::move(pr)).first->second;
}

void report(benchmark::State& state, int iterations, int applications, double kkt, bool converged) {
  state.counters["qp_iterations"] = iterations;
  state.counters["operator_applications"] = applications;
  state.counters["kkt_residual"] = kkt;
  state.counters["converged"] = converged ? 1 : 0;
}

void BM_Tresca(benchmark::State& state) {
  const Problem& pr = problem(state.range(0));
  const auto algorithm = static_cast<TrescaAlgorithm>(state.range(1));
  TrescaSolver::Options options;
  options.algorithm = algorithm;
  const TrescaSolver solver(*pr.op, FrictionLaw::regular_polygon(0.3, 8), options);
  // Slip bounds from a pressure estimate: μ·max(0, −c_ν) (zero on lifted nodes), as in the
  // first friction step of a fixed point.
  Eigen::VectorXd s(pr.nodes);
  for (Eigen::Index i = 0; i < pr.nodes; ++i) s(i) = std::max(0.0, -pr.c(3 * i + 2));
  TrescaSolver::Summary summary;
  for (auto _ : state) {
    ContactState contact;
    summary = solver.solve(pr.c, s, contact);
    benchmark::DoNotOptimize(contact.z.data());
  }
  state.counters["nodes"] = static_cast<double>(pr.nodes);
  report(state, summary.iterations, summary.operator_applications, summary.kkt_residual,
         summary.converged());
  state.SetLabel(std::string(to_string(algorithm)));
}

void BM_Coulomb(benchmark::State& state) {
  const Problem& pr = problem(state.range(0));
  const CoulombSolver solver(*pr.op, FrictionLaw::regular_polygon(0.3, 8));
  CoulombSolver::Summary summary;
  for (auto _ : state) {
    ContactState contact;
    summary = solver.solve(pr.c, contact);
    benchmark::DoNotOptimize(contact.z.data());
  }
  state.counters["nodes"] = static_cast<double>(pr.nodes);
  state.counters["fixed_point_iterations"] = summary.iterations;
  report(state, summary.qp_iterations, summary.operator_applications, summary.kkt_residual,
         summary.converged());
}

// Grid sides 10, 32, 50: 100, 1024, 2500 nodes.
BENCHMARK(BM_Tresca)
    ->ArgsProduct({{10, 32, 50},
                   {static_cast<long>(TrescaAlgorithm::kJointMpgp), static_cast<long>(TrescaAlgorithm::kSplit)}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK(BM_Coulomb)->Arg(10)->Arg(32)->Arg(50)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
