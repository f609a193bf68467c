// SPDX-License-Identifier: MIT
// The frictopt command line: parses arguments (CLI11) and dispatches to the subcommands in
// *_command.cpp. Usage errors exit 2 like every other invalid input; exceptions are mapped to
// exit codes in one place (exit_codes.cpp). No numerics live here.
#include <CLI/CLI.hpp>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/mesh/gmsh_mesh.hpp"
#include "frictopt/study/build_mesh.hpp"
#include "frictopt/linalg/blas_threads.hpp"
#ifdef FRICTOPT_HAVE_PETSC
#include <unistd.h>

#include <cstdio>

#include "frictopt/petsc/petsc_session.hpp"
#endif

using namespace frictopt::app;

namespace {

// CLI::Range lets NaN through (NaN fails both of its comparisons): numbers must be finite first.
const CLI::Validator kFiniteNumber(
    [](std::string& text) {
      try {
        std::size_t used = 0;
        const double value = std::stod(text, &used);
        if (used == text.size() && std::isfinite(value)) return std::string();
      } catch (const std::exception&) {
      }
      return "'" + text + "' is not a finite number";
    },
    "FINITE");

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"frictopt: shape optimization of elastic bodies in contact with (anisotropic) Coulomb friction"};
  app.require_subcommand(1);
  // The version and the BLAS this binary actually calls (the library dgemm_ binds to; a slow
  // reference BLAS or ATLAS shows here, docs/benchmarks.md "Which BLAS").
  app.set_version_flag("--version", [] {
    return std::string("frictopt ") + FRICTOPT_VERSION + "\nBLAS: " + frictopt::linalg::describe_loaded_blas() + "\n" +
           frictopt::linalg::describe_blas_threads();
  });
  std::filesystem::path case_path, out_dir = "out";
  CLI::App* solve = app.add_subcommand("solve", "Solve the state problem of a case at its initial design and write VTK");
  solve->add_option("case", case_path, "case file (TOML), see docs/case-format.md")->required()->check(CLI::ExistingFile);
  solve->add_option("-o,--output", out_dir, "output directory (created if missing)");
  std::filesystem::path fclib_out;
  std::string fclib_units = "normalized";
  bool fclib_no_solution = false;
  CLI::App* export_fclib = app.add_subcommand(
      "export-fclib", "Write the frictional contact problem at the initial design in FCLIB's local format (HDF5)");
  export_fclib->add_option("case", case_path, "case file (TOML) with an isotropic [contact.friction]")
      ->required()
      ->check(CLI::ExistingFile);
  export_fclib->add_option("out", fclib_out, "output file (.hdf5), replaced if it exists")->required();
  export_fclib->add_option("--units", fclib_units,
                           "normalized (default: units of our solution's largest force and displacement, O(1) "
                           "data) or si")
      ->check(CLI::IsMember({"normalized", "si"}));
  export_fclib->add_flag("--no-solution", fclib_no_solution, "do not store our solution");
  std::filesystem::path design_path;
  double relative_step = 1e-4;
  CLI::App* check_gradient = app.add_subcommand(
      "check-gradient", "Compare the adjoint subgradient with central differences of the cost, per component");
  check_gradient->add_option("case", case_path, "case file (TOML) with [contact] and [cost]")
      ->required()
      ->check(CLI::ExistingFile);
  check_gradient->add_option("--design", design_path, "design file (JSON with \"alpha\", or numbers); default: the case's initial design")
      ->check(CLI::ExistingFile);
  check_gradient->add_option("--step", relative_step, "finite-difference step relative to the width of each design variable's bounds (C0 for a control height)")
      ->check(kFiniteNumber & CLI::Range(1e-10, 1e-1));
  bool resume = false, force = false;
  CLI::App* optimize = app.add_subcommand("optimize", "Minimize the case's cost over the admissible designs (bundle trust method)");
  optimize->add_option("case", case_path, "case file (TOML) with [contact] and [cost]")->required();
  optimize->add_option("-o,--output", out_dir, "run directory (history, checkpoint, VTK series, summary)");
  optimize->add_flag("--resume", resume, "continue the run in the output directory from its checkpoint");
  optimize->add_flag("--force", force, "replace an existing run in the output directory");
  std::filesystem::path run_dir;
  int certify_cap = 4096;
  CLI::App* certify = app.add_subcommand("certify", "Optimality certificate of a run's final design (thesis 5.3)");
  certify->add_option("run_dir", run_dir, "run directory written by `frictopt optimize`")->required();
  certify->add_option("--cap", certify_cap, "largest |L| enumerated in full (else sampled)")->check(CLI::Range(1, 1 << 20));
  double certify_radius = 0.0;
  int certify_samples = 0;
  certify
      ->add_option("--sample-radius", certify_radius,
                   "also a sampled (Goldstein) certificate with designs within this radius [m] of the final one")
      ->check(CLI::NonNegativeNumber);
  certify->add_option("--samples", certify_samples, "designs sampled with --sample-radius (default 10(d + 1))")
      ->check(CLI::Range(1, 100000));
  std::filesystem::path export_design;
  CLI::App* export_shape = app.add_subcommand(
      "export-shape", "A run's design out: the design patch as STEP, the body as Gmsh .msh and STL (docs/meshes.md)");
  export_shape->add_option("run_dir", run_dir, "run directory written by `frictopt optimize`")->required();
  export_shape->add_option("--design", export_design, "design JSON to export instead of the run's final_design.json")
      ->check(CLI::ExistingFile);
  bool identify_generate = false, identify_noise_free = false;
  std::uint64_t identify_seed = 1;
  CLI::App* identify = app.add_subcommand(
      "identify", "Identify friction coefficients (and E) from measured contact data (Ceres least squares)");
  identify->add_option("case", case_path, "case file (TOML) with [contact] and [identification]")
      ->required()
      ->check(CLI::ExistingFile);
  identify->add_option("-o,--output", out_dir, "output directory (fit.csv, summary.json, ceres_report.txt)");
  identify->add_flag("--generate-synthetic", identify_generate,
                     "write DIR/measurements.csv: the measurement rows with values from the case's own law plus noise");
  identify->add_option("--seed", identify_seed, "seed of the synthetic noise (std::mt19937_64)");
  identify->add_flag("--noise-free", identify_noise_free, "synthetic values without noise");
  CLI::App* experiment = app.add_subcommand(
      "experiment", "Virtual tribometer: press, then pull at angles θ until gross sliding (docs/experiments.md)");
  experiment->add_option("case", case_path, "case file (TOML) with [contact] and [experiment]")
      ->required()
      ->check(CLI::ExistingFile);
  experiment->add_option("-o,--output", out_dir, "output directory (tribometer_*.csv, summary.json)");
  // Every command that reads a case: the restricted reading of .geo files and the memory limit
  // (docs/meshes.md, "A .geo file runs no code"; docs/case-format.md, "Size limits").
  bool trust_geo = false;
  double max_memory_gb = 0.0;
  for (CLI::App* command :
       {solve, export_fclib, check_gradient, optimize, certify, export_shape, identify, experiment}) {
    command->add_flag("--trust-geo", trust_geo,
                      "run the case's .geo file with every Gmsh command (System, file writes, ...); only for a "
                      "file you have read and trust");
    command->add_option("--max-memory", max_memory_gb, "refuse a body whose solve would need more memory [GB] "
                                                       "(default: the memory available)")
        ->check(kFiniteNumber)
        ->check(CLI::Range(0.001, 1e6));
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help prints and exits 0; every usage error (CLI11's codes 105, 106, 109, ...) is
    // invalid input, exit 2 as documented.
    return app.exit(e) == 0 ? kExitOk : kExitInvalidInput;
  }
#ifdef FRICTOPT_HAVE_PETSC
  // PETSc/MPI lifetime (docs/petsc-engine.md): the guard initializes PETSc only when a case selects
  // engine = "petsc", so a direct run never needs mpirun. Under mpirun every rank runs the
  // command (the engine is collective); rank 0 alone prints and writes into the output
  // directory, the other ranks write into a private scratch directory removed at the end.
  const frictopt::petsc::PetscSession petsc_session;
  std::filesystem::path scratch;
  if (frictopt::petsc::PetscSession::launcher_rank() > 0) {
    std::string pattern = (std::filesystem::temp_directory_path() / "frictopt-rank-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) {
      std::fprintf(stderr, "error: rank %d could not create its scratch directory\n",
                   frictopt::petsc::PetscSession::launcher_rank());
      return kExitInvalidInput;
    }
    scratch = pattern;
    out_dir = scratch / "out";
    if (std::freopen("/dev/null", "w", stdout) == nullptr) return kExitInvalidInput;
  }
  struct ScratchRemoval {
    const std::filesystem::path& path;
    ~ScratchRemoval() {
      std::error_code ignored;
      if (!path.empty()) std::filesystem::remove_all(path, ignored);  // only files this run wrote
    }
  } scratch_removal{scratch};
#endif
  frictopt::mesh::set_trust_geo_by_default(trust_geo);
  if (max_memory_gb > 0) frictopt::study::set_memory_limit(static_cast<std::uint64_t>(max_memory_gb * 1e9));
  return run_guarded([&] {
    if (*solve) return run_solve(case_path, out_dir);
    if (*optimize) {
      if (resume && force) throw frictopt::InvalidInput("--resume and --force exclude each other; choose one");
#ifdef FRICTOPT_HAVE_PETSC
      if (resume && frictopt::petsc::PetscSession::launcher_size() > 1) mirror_run_for_resume(out_dir);
#endif
      return run_optimize(case_path, out_dir, resume, force);
    }
    if (*check_gradient) return run_check_gradient(case_path, design_path, relative_step);
    if (*certify) return run_certify(run_dir, certify_cap, certify_radius, certify_samples);
    if (*export_shape) return run_export_shape(run_dir, export_design);
    if (*identify) return run_identify(case_path, out_dir, identify_generate, identify_seed, identify_noise_free);
    if (*experiment) return run_experiment(case_path, out_dir);
    if (*export_fclib) return run_export_fclib(case_path, fclib_out, fclib_units, !fclib_no_solution);
    return kExitOk;
  });
}
