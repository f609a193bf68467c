// SPDX-License-Identifier: MIT
// Loading programs (docs/experiments.md §6): a program of K steps reuses ONE factorization of the
// stiffness and one Delassus matrix. Reported against the natural floor, one factorization
// (+ M) + K contact solves, and against K independent static solves (K factorizations).
// The body is the punch of cases3d/punch (dish-shaped bottom, 16-gon μ = 0.3) pressed down and
// sideways in K proportional steps.
//   build/bench/experiments/program_bench --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <chrono>

#include "frictopt/study/loading_program.hpp"
#include "common/timing.hpp"
#include "common/punch.hpp"

namespace {

using frictopt::bench::Clock;
using frictopt::bench::seconds;
using frictopt::bench::punch;

void BM_LoadingProgram(benchmark::State& state) {
  using namespace frictopt;
  const int n = static_cast<int>(state.range(0)), K = static_cast<int>(state.range(1));
  const study::BodyDefinition definition = punch(n, n / 2);
  study::LoadingProgramDefinition program;
  for (int k = 1; k <= K; ++k) {
    study::LoadStepDefinition step;
    step.dirichlet_scale = {double(k) / K};
    program.steps.push_back(step);
  }
  double program_s = 0, factorization_s = 0, contact_s = 0, independent_s = 0;
  int factorizations = 0, unknowns = 0;
  for (auto _ : state) {
    study::ElasticBody body(definition);
    study::LoadingProgram runner(body, program);
    double first_contact = 0.0;
    const auto t0 = Clock::now();
    const auto summary = runner.run(definition.initial_design, [&](const study::LoadStepResult& r) {
      if (r.step == 1) first_contact = r.state.contact->summary.time_seconds;
      // The setup of step 1 (factorization, dense M; with the step's recovery of u and the
      // stresses) is the one-time cost of the program.
      if (r.step == 1)
        factorization_s =
            r.state.summary.factorization_seconds + r.state.summary.solve_seconds - first_contact;
    });
    program_s = seconds(t0, Clock::now());
    if (summary.status != Status::kConverged) state.SkipWithError(summary.message.c_str());
    contact_s = summary.contact_seconds;
    factorizations = summary.factorizations;
    unknowns = body.elasticity().dofs().num_free();
    // K independent static solves of the same loads: a fresh body (and factorization) per step.
    const auto t1 = Clock::now();
    for (int k = 1; k <= K; ++k) {
      study::BodyDefinition d = definition;
      d.dirichlet[0].displacement *= double(k) / K;
      study::ElasticBody fresh(d);
      benchmark::DoNotOptimize(fresh.solve(d.initial_design).displacement.data());
    }
    independent_s = seconds(t1, Clock::now());
  }
  state.counters["unknowns"] = unknowns;
  state.counters["K"] = K;
  state.counters["program_s"] = program_s;
  state.counters["factorization_and_M_s"] = factorization_s;
  state.counters["contact_solves_s"] = contact_s;
  state.counters["floor_s"] = factorization_s + contact_s;
  state.counters["program_over_floor"] = program_s / (factorization_s + contact_s);
  state.counters["independent_s"] = independent_s;
  state.counters["independent_over_program"] = independent_s / program_s;
  state.counters["factorizations"] = factorizations;
}

BENCHMARK(BM_LoadingProgram)
    ->ArgNames({"cells", "K"})
    ->Args({16, 8})
    ->Args({24, 8})
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
