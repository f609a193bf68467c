// SPDX-License-Identifier: MIT
// Solver outcome shared by all Summaries: non-convergence is a Status, not an
// exception. Spellings come from one table, so reports and parsers cannot drift.
#pragma once

#include <limits>
#include <string_view>

namespace frictopt {

enum class Status {
  kNotRun,            ///< solve() has not been called
  kConverged,         ///< stopping test met
  kMaxIterations,     ///< iteration or evaluation limit reached first
  kStalled,           ///< no progress possible at working precision
  kDiverged,          ///< iterates or residuals grew without bound
  kNumericalFailure,  ///< e.g. a non-positive pivot, NaN from an oracle
  kStoppedByCallback  ///< an IterationCallback returned CallbackResult::kStop
};

/// "converged", "max_iterations", ... (the spelling used in reports, JSON and the CLI).
std::string_view to_string(Status status);
/// Inverse of to_string; throws InvalidInput naming the accepted spellings.
Status parse_status(std::string_view text);

/// Returned by iteration callbacks: continue, or stop the solver cleanly.
enum class CallbackResult { kContinue, kStop };

/// Marks numbers a Summary has not computed (yet): they stay NaN so they cannot pass for results.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace frictopt
