// SPDX-License-Identifier: MIT
// One Coulomb state solve and one subgradient on 3D punch problems of about 20k, 100k and 200k
// unknowns (625, 1681 and 2601 contact nodes), against the floor of one sparse Cholesky
// factorization + solve of the same stiffness matrix (docs/benchmarks.md §2).
//   build/bench/study/contact_benchmark                 (all sizes; the largest takes minutes)
//   build/bench/study/contact_benchmark --benchmark_filter=cells:24/
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>

#include "frictopt/cost/cost_functional.hpp"
#include "frictopt/study/shape_oracle.hpp"
#include "common/timing.hpp"
#include "common/punch.hpp"

namespace {

using frictopt::bench::Clock;
using frictopt::bench::seconds;
using frictopt::bench::peak_rss_megabytes;
using frictopt::bench::punch;

void BM_CoulombSolveAndSubgradient(benchmark::State& state) {
  using namespace frictopt;
  const int n = static_cast<int>(state.range(0));
  const study::BodyDefinition definition = punch(n, static_cast<int>(state.range(1)));
  double floor_s = 0, state_s = 0, subgradient_s = 0, factorization_s = 0;
  int unknowns = 0, contact_nodes = 0, fixed_point = 0, qp = 0, applies = 0;
  double kkt = 0;
  for (auto _ : state) {
    // Floor: one factorization (CHOLMOD's own ordering) + one solve of the same matrix.
    {
      study::BodyDefinition plain = definition;
      plain.contact.reset();
      study::ElasticBody elastic(plain);
      const auto t0 = Clock::now();
      const study::BodyState s = elastic.solve(plain.initial_design);
      floor_s = seconds(t0, Clock::now()) - s.summary.assembly_seconds;
      benchmark::DoNotOptimize(s.displacement.data());
    }
    study::ElasticBody body(definition);
    study::ShapeOracle oracle(body, cost::make_compliance());
    const auto t0 = Clock::now();
    const study::Evaluation& e = oracle.evaluate_design(definition.initial_design, false);
    const auto t1 = Clock::now();
    const study::Evaluation& g = oracle.evaluate_design(definition.initial_design, true);
    const auto t2 = Clock::now();
    if (!g.ok) state.SkipWithError(g.message.c_str());
    state_s = seconds(t0, t1) - e.state.assembly_seconds;
    subgradient_s = seconds(t1, t2);
    factorization_s = e.state.factorization_seconds;
    unknowns = body.elasticity().dofs().num_free();
    contact_nodes = static_cast<int>(body.contact_boundary()->num_nodes());
    fixed_point = e.contact.iterations;
    qp = e.contact.qp_iterations;
    applies = e.contact.operator_applications;
    kkt = e.contact.kkt_residual;
  }
  state.counters["unknowns"] = unknowns;
  state.counters["contact_nodes"] = contact_nodes;
  state.counters["floor_s"] = floor_s;
  state.counters["state_s"] = state_s;
  state.counters["factorization_s"] = factorization_s;
  state.counters["subgradient_s"] = subgradient_s;
  state.counters["state_over_floor"] = state_s / floor_s;
  state.counters["subgradient_over_state"] = subgradient_s / state_s;
  state.counters["fixed_point_its"] = fixed_point;
  state.counters["qp_its"] = qp;
  state.counters["applies"] = applies;
  state.counters["kkt"] = kkt;
  state.counters["peak_rss_MB"] = peak_rss_megabytes();
}

// (cells, layers) = (24, 12), (40, 20), (50, 26): 3·25²·12 = 22.5k, 3·41²·20 ≈ 101k and
// 3·51²·26 ≈ 203k free unknowns (the top layer is prescribed) with 625, 1681, 2601 contact nodes.
BENCHMARK(BM_CoulombSolveAndSubgradient)
    ->ArgNames({"cells", "layers"})
    ->Args({24, 12})
    ->Args({40, 20})
    ->Args({50, 26})
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
