// SPDX-License-Identifier: MIT
// The error of an operation the file system refused (a full disk, a read-only mount, missing
// permissions, a short write): the command line answers exit 5, the Python module OSError
// (README, "Command line"). It is a std::filesystem::filesystem_error, so every layer that
// already maps that type maps this one the same way; its what() is frictopt's own one-line
// message, naming the file and the system's reason.
#pragma once

#include <cerrno>
#include <filesystem>
#include <string>
#include <system_error>

namespace frictopt::io {

class FileSystemError : public std::filesystem::filesystem_error {
 public:
  /// `message` names the file and what failed; `error` is the errno value (0: unknown).
  FileSystemError(std::string message, const std::filesystem::path& path, int error = 0)
      : std::filesystem::filesystem_error(message, path, std::error_code(error, std::generic_category())),
        message_(std::move(message)) {}
  [[nodiscard]] const char* what() const noexcept override { return message_.c_str(); }

 private:
  std::string message_;
};

}  // namespace frictopt::io
