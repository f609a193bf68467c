// SPDX-License-Identifier: MIT
// How frictopt reads a run's files and the other inputs it names (checkpoint, design, history,
// measurements; docs/case-format.md, "Run directories"): only regular files, opened without
// blocking — a FIFO or a device in place of checkpoint.json is refused at once instead of
// waiting forever for a writer — and never more than a bound of bytes.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace frictopt::io::detail {

/// Reads at most `max_bytes` of the regular file `path` (a symbolic link to one is followed).
/// Throws InvalidInput naming `path` and `what` ("the checkpoint") when it is missing, not a
/// regular file, or larger than `max_bytes`; FileSystemError when the system refuses to read it.
[[nodiscard]] std::string read_input_file(const std::filesystem::path& path, std::string_view what,
                                          std::size_t max_bytes);

/// `text` shortened to at most `max_chars` characters for an error message, with any byte
/// that is not printable ASCII shown as '?' (a binary file never reaches the terminal).
[[nodiscard]] std::string printable_excerpt(std::string_view text, std::size_t max_chars = 60);

}  // namespace frictopt::io::detail
