// SPDX-License-Identifier: MIT
// Reading a design vector α from a file: a JSON object with an "alpha" array (as frictopt's
// summary.json and final_design.json write it) or plain text numbers separated by spaces,
// commas or newlines (# starts a comment).
#pragma once

#include <Eigen/Core>
#include <filesystem>

namespace frictopt::io {

/// Throws InvalidInput naming the file and what is wrong (unreadable, no "alpha", a non-number,
/// or a length other than `expected_size`).
[[nodiscard]] Eigen::VectorXd read_design_file(const std::filesystem::path& path, Eigen::Index expected_size);

}  // namespace frictopt::io
