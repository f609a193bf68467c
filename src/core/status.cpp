// SPDX-License-Identifier: MIT
#include "frictopt/core/status.hpp"

#include <array>
#include <string>
#include <utility>

#include "frictopt/core/error.hpp"

namespace frictopt {
namespace {
constexpr std::array<std::pair<Status, std::string_view>, 7> kStatusNames{{
    {Status::kNotRun, "not_run"},
    {Status::kConverged, "converged"},
    {Status::kMaxIterations, "max_iterations"},
    {Status::kStalled, "stalled"},
    {Status::kDiverged, "diverged"},
    {Status::kNumericalFailure, "numerical_failure"},
    {Status::kStoppedByCallback, "stopped_by_callback"},
}};
}  // namespace

std::string_view to_string(Status status) {
  for (const auto& [value, name] : kStatusNames)
    if (value == status) return name;
  return "unknown";
}

Status parse_status(std::string_view text) {
  std::string accepted;
  for (const auto& [value, name] : kStatusNames) {
    if (name == text) return value;
    accepted += (accepted.empty() ? "" : ", ") + std::string(name);
  }
  throw InvalidInput("status '" + std::string(text) + "' is unknown; expected one of " + accepted);
}

}  // namespace frictopt
