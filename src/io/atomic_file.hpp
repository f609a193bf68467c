// SPDX-License-Identifier: MIT
// Whole-file writes that a concurrent reader (ParaView, a plotting script) never sees half
// done: write a sibling temporary file, then rename it over the target (atomic on POSIX
// within one file system).
#pragma once

#include <filesystem>
#include <string_view>

namespace frictopt::io::detail {

/// Replaces `path` by `content`. Throws InvalidInput naming the path if it cannot be written.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace frictopt::io::detail
