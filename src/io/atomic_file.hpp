// SPDX-License-Identifier: MIT
// How frictopt writes an output file (docs/case-format.md, "Output files"):
//  - only regular files: an existing symbolic link, device, FIFO, socket or directory at the
//    target is refused (InvalidInput naming it), never replaced and never written through — a
//    link could send a run's output anywhere, and replacing /dev/null by a regular file (as
//    root) damages the system;
//  - whole files are replaced atomically: the content goes to a new, uniquely named sibling
//    (created with O_EXCL, so no existing file is ever clobbered) that is renamed over the
//    target, so a concurrent reader (ParaView, a plotting script) never sees a half-written file.
#pragma once

#include <filesystem>
#include <string_view>

namespace frictopt::io::detail {

/// Throws InvalidInput unless `path` is absent or a regular file (not following a final
/// symbolic link), naming what it is instead.
void require_regular_output(const std::filesystem::path& path);

/// A fresh, uniquely named empty file next to `path` (".<name>.XXXXXX.tmp"), for writers that
/// produce the file themselves (VTK, HDF5) before publish_file renames it over `path`.
[[nodiscard]] std::filesystem::path make_sibling_temporary(const std::filesystem::path& path);

/// Renames `temporary` over `path` (after require_regular_output); removes `temporary` and
/// throws (InvalidInput for a target that is not a regular file, FileSystemError when the
/// rename fails) on failure.
void publish_file(const std::filesystem::path& temporary, const std::filesystem::path& path);

/// Replaces `path` by `content` as above. A short write or a failed close (a full disk, a
/// read-only file system) throws FileSystemError naming the path, removes the temporary and
/// leaves the previous file at `path` as it was.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// Writes all of `content` to the open descriptor `fd` (retrying interrupted and partial
/// writes); throws FileSystemError naming `target` when the system accepts less than all of it.
void write_all(int fd, std::string_view content, const std::filesystem::path& target);

}  // namespace frictopt::io::detail
