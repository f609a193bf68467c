// SPDX-License-Identifier: MIT
// The bundle trust method's state as JSON, so `frictopt optimize --resume` continues exactly
// where an interrupted run stopped (at most the current iteration is lost).
#pragma once

#include <filesystem>

#include "frictopt/io/json.hpp"
#include "frictopt/optim/bundle_trust.hpp"

namespace frictopt::io {

/// Every field of the iteration summary (doubles round-trip exactly: JSON numbers are written
/// with 17 significant digits).
[[nodiscard]] JsonValue checkpoint_to_json(const optim::BundleTrust::IterationSummary& state);
/// Inverse of checkpoint_to_json; throws InvalidInput naming the missing or malformed field.
[[nodiscard]] optim::BundleTrust::IterationSummary checkpoint_from_json(const JsonValue& json);

/// Reads a checkpoint file written by write_json(checkpoint_to_json(...)).
[[nodiscard]] optim::BundleTrust::IterationSummary read_checkpoint(const std::filesystem::path& path);

}  // namespace frictopt::io
