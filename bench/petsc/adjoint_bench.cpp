// SPDX-License-Identifier: MIT
// The PETSc engine's subgradient against its state (docs/scaling.md): one
// Coulomb state and one subgradient ξ (one transposed Krylov solve) of a 3D case at a given
// grid, with the case's cost (target pressure for punch-anisotropic: ∇_z J ≠ 0). Prints one
// line from rank 0: unknowns, contact nodes, Newton/Krylov iterations of the state, Krylov
// iterations and true relative residual of the adjoint, wall and CPU seconds of each part
// (CPU: this rank's process time, robust to other load on a shared machine) and their ratio.
//   mpiexec -n 2 build/bench/petsc/adjoint_bench cases3d/punch-anisotropic/case.toml 110 110 26
// A run with engine = "petsc" is forced (the case's [solver] table is otherwise kept).
#include <fmt/format.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <string>

#include "frictopt/io/case_file.hpp"
#include "frictopt/petsc/petsc_session.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/shape_oracle.hpp"
#include "common/timing.hpp"

namespace {

using frictopt::bench::Clock;
using frictopt::bench::seconds_since;
using frictopt::bench::peak_rss_megabytes;
double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }
}  // namespace

int main(int argc, char** argv) {
  using namespace frictopt;
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s CASE.toml NX NY NZ\n", argv[0]);
    return 2;
  }
  const petsc::PetscSession session;
  try {
    io::CaseDescription c = io::load_case(argv[1]);
    c.body.resolution.cells = {std::atoi(argv[2]), std::atoi(argv[3]), std::atoi(argv[4])};
    c.body.engine.kind = study::StateEngine::kPetsc;
    study::ElasticBody body(c.body);
    auto start = Clock::now();
    double cpu = cpu_seconds();
    study::ShapeOracle oracle(body, c.required_cost());  // solves the state when the cost's target needs it
    const study::Evaluation& state = oracle.evaluate_design(c.body.initial_design, false);
    const double state_wall = seconds_since(start), state_cpu = cpu_seconds() - cpu;
    if (!state.ok) throw NumericalFailure("state: " + state.message);
    start = Clock::now();
    cpu = cpu_seconds();
    const study::Evaluation& e = oracle.evaluate_design(c.body.initial_design, true);
    const double adjoint_wall = seconds_since(start), adjoint_cpu = cpu_seconds() - cpu;
    if (!e.ok) throw NumericalFailure("subgradient: " + e.message);
    if (petsc::PetscSession::rank() == 0) {
      const Eigen::Index unknowns = body.mesh().num_dofs();
      fmt::print("ranks={} cells={}x{}x{} unknowns={} contact_nodes={} state: [{} Newton / {} Krylov] wall={:.1f}s "
                 "cpu={:.1f}s | subgradient: [{}] wall={:.1f}s cpu={:.1f}s | ratio wall={:.2f} cpu={:.2f} | "
                 "max_rss(rank 0)={:.0f}MB |ξ|={:.6e}\n",
                 petsc::PetscSession::size(), argv[2], argv[3], argv[4], unknowns,
                 body.contact_boundary()->num_nodes(), e.contact.iterations, e.contact.qp_iterations, state_wall,
                 state_cpu, e.adjoint.message, adjoint_wall, adjoint_cpu, adjoint_wall / state_wall,
                 adjoint_cpu / state_cpu, peak_rss_megabytes(), e.subgradient.norm());
    }
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "adjoint_bench: %s\n", error.what());
    return 3;
  }
}
