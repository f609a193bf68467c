// SPDX-License-Identifier: MIT
// The exit codes of the frictopt command line and the one place that maps every exception to
// one of them (README "Command line"). A command returns kExitOk, kExitNumericalFailure or
// kExitNeedsAttention itself; everything thrown ends here, is printed as one "error: ..." line, and never
// escapes main (no std::terminate, no exit 134).
#pragma once

#include <functional>

namespace frictopt::app {

inline constexpr int kExitOk = 0;
/// An exception no layer expected (a bug): the message and "please report" are printed.
inline constexpr int kExitInternalError = 1;
/// Bad input: the case, a CLI argument (also CLI11's usage errors), a design or measurement
/// file, a run directory that is refused (foreign files, locked by another run, wrong case).
inline constexpr int kExitInvalidInput = 2;
/// A solver failed (a status other than converged, or NumericalFailure): the one-line report
/// says what failed.
inline constexpr int kExitNumericalFailure = 3;
/// std::bad_alloc: the problem does not fit in memory.
inline constexpr int kExitOutOfMemory = 4;
/// The file system refused an operation (permissions, a full disk, a path that is not a
/// directory): std::filesystem::filesystem_error and std::ios_base::failure.
inline constexpr int kExitFileSystem = 5;
/// Finished without a certificate: the result was written but needs the user's attention before
/// it is used — `optimize` stalled without certifying stationarity, or ended at a design with no
/// contact (study::OptimizationOutcome); `check-gradient` found a component no kink explains or
/// a check that cannot mean anything. The reasons are printed and in summary.json ("attention").
inline constexpr int kExitNeedsAttention = 6;

/// Runs `command` and returns its exit code; any exception is printed to stderr and mapped to
/// the codes above.
int run_guarded(const std::function<int()>& command);

}  // namespace frictopt::app
