// SPDX-License-Identifier: MIT
// The subcommands of the frictopt command line, one file each (*_command.cpp). They load the
// case through io, call study, print one-line reports and return the exit code; main.cpp only
// parses arguments. Exceptions are mapped to exit codes in exit_codes.cpp.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "exit_codes.hpp"
#include "frictopt/io/case_description.hpp"

namespace frictopt::app {


int run_solve(const std::filesystem::path& case_path, const std::filesystem::path& out_dir);
/// `solve` of a case with [[program.step]] tables: one state per step (experiment_command.cpp).
int run_program(const std::filesystem::path& case_path, const std::filesystem::path& out_dir,
                const io::CaseDescription& description);
/// `experiment`: the virtual tribometer of the case's [experiment] table.
int run_experiment(const std::filesystem::path& case_path, const std::filesystem::path& out_dir);
int run_export_fclib(const std::filesystem::path& case_path, const std::filesystem::path& out_path,
                     const std::string& units, bool include_solution);
int run_check_gradient(const std::filesystem::path& case_path, const std::filesystem::path& design_path,
                       double relative_step);
int run_optimize(const std::filesystem::path& case_argument, const std::filesystem::path& out_dir, bool resume,
                 bool force);
#ifdef FRICTOPT_HAVE_PETSC
/// optimize --resume under mpirun (docs/petsc-engine.md): rank 0 owns the run directory `out_dir`
/// (its lock, checkpoint and history); it broadcasts the files a resume reads (case.toml,
/// checkpoint.json, history.csv) and every other rank writes them into its own `out_dir` (its
/// scratch directory), so that every rank's bundle method resumes from rank 0's checkpoint.
/// Collective.
void mirror_run_for_resume(const std::filesystem::path& out_dir);
#endif
int run_certify(const std::filesystem::path& run_dir, int cap, double sample_radius = 0.0, int samples = 0);
/// `export-shape`: the run's design as STEP, .msh and STL (io::export_shape).
int run_export_shape(const std::filesystem::path& run_dir, const std::filesystem::path& design_path);
int run_identify(const std::filesystem::path& case_path, const std::filesystem::path& out_dir, bool generate,
                 std::uint64_t seed, bool noise_free);

}  // namespace frictopt::app
