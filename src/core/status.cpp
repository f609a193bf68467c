// SPDX-License-Identifier: MIT
#include "frictopt/core/status.hpp"

#include <array>
#include <string>
#include <utility>

#include "frictopt/core/enum_table.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt {
namespace {
constexpr frictopt::detail::EnumTable<Status, 7> kStatusNames{{{
    {Status::kNotRun, "not_run"},
    {Status::kConverged, "converged"},
    {Status::kMaxIterations, "max_iterations"},
    {Status::kStalled, "stalled"},
    {Status::kDiverged, "diverged"},
    {Status::kNumericalFailure, "numerical_failure"},
    {Status::kStoppedByCallback, "stopped_by_callback"},
}}};
}  // namespace

std::string_view to_string(Status status) { return kStatusNames.name(status); }

Status parse_status(std::string_view text) { return kStatusNames.parse(text, "status"); }

}  // namespace frictopt
