// SPDX-License-Identifier: MIT
// The Delassus operator's two representations at contact sizes m = 1,500, 5,043 (punch-large:
// 1,681 nodes) and 7,803 (2,601 nodes): one product through the Schur factor L (two triangular
// solves, dtrsv) vs one product with the dense M (dsymv), the cost of forming the dense M from L
// (dpotri), and the block M[R, T] of the nodes in contact that the adjoint needs (61 % of the
// unknowns, as in punch-large) either way. These numbers set
// study::ContactDefinition::dense_delassus_max_unknowns (docs/benchmarks.md §2).
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <map>
#include <memory>
#include <vector>

#include "frictopt/contact/delassus.hpp"

extern "C" void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info);

namespace {

using namespace frictopt::contact;

/// The lower Cholesky factor of a well-conditioned SPD matrix of size m (LAPACK, like CHOLMOD's
/// trailing block), cached per size.
const Eigen::MatrixXd& schur_factor(int m) {
  static std::map<int, Eigen::MatrixXd> cache;
  auto it = cache.find(m);
  if (it != cache.end()) return it->second;
  Eigen::MatrixXd B = Eigen::MatrixXd::Random(m, m);
  Eigen::MatrixXd L = B * B.transpose() / m;
  L.diagonal().array() += 1.0;
  int info = 0;
  dpotrf_("L", &m, L.data(), &m, &info);
  L.triangularView<Eigen::StrictlyUpper>().setZero();
  return cache.emplace(m, std::move(L)).first->second;
}

std::vector<Eigen::Index> every_fifth_dropped_twice(int m) {  // ≈ 61 % of the indices
  std::vector<Eigen::Index> rows;
  for (int k = 0; k < m; ++k)
    if (k % 5 != 1 && k % 5 != 3) rows.push_back(k);
  return rows;
}

/// Times y = M x for one operator (the Google Benchmark loop).
void time_products(benchmark::State& state, const DelassusMatrix& op) {
  const Eigen::VectorXd x = Eigen::VectorXd::Random(op.size());
  Eigen::VectorXd y(op.size());
  for (auto _ : state) {
    op.apply(x, y);
    benchmark::DoNotOptimize(y.data());
  }
}

void BM_SchurApply(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0));
  time_products(state, SchurDelassus(schur_factor(m), 3));
}

void BM_DenseApply(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0));
  time_products(state, DenseDelassus(SchurDelassus(schur_factor(m), 3).dense()));
}

void BM_FormDense(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0));
  const SchurDelassus op(schur_factor(m), 3);
  for (auto _ : state) benchmark::DoNotOptimize(op.dense().data());
}

void BM_ActiveBlockFromSchur(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0));
  const SchurDelassus op(schur_factor(m), 3);
  const auto rows = every_fifth_dropped_twice(m);
  for (auto _ : state) benchmark::DoNotOptimize(op.block(rows, rows).data());
}

void BM_ActiveBlockFromDense(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0));
  const DenseDelassus op(SchurDelassus(schur_factor(m), 3).dense());
  const auto rows = every_fifth_dropped_twice(m);
  for (auto _ : state) benchmark::DoNotOptimize(op.block(rows, rows).data());
}

BENCHMARK(BM_SchurApply)->Arg(1500)->Arg(5043)->Arg(7803)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DenseApply)->Arg(1500)->Arg(5043)->Arg(7803)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FormDense)->Arg(1500)->Arg(5043)->Arg(7803)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_ActiveBlockFromSchur)->Arg(1500)->Arg(5043)->Arg(7803)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_ActiveBlockFromDense)->Arg(1500)->Arg(5043)->Arg(7803)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
