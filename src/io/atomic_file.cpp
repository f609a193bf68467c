// SPDX-License-Identifier: MIT
#include "atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>
#include <vector>

#include "frictopt/core/error.hpp"
#include "frictopt/io/file_error.hpp"

namespace frictopt::io::detail {
namespace {

std::string kind_of(const std::filesystem::file_status& status) {
  using std::filesystem::file_type;
  switch (status.type()) {
    case file_type::symlink: return "a symbolic link";
    case file_type::directory: return "a directory";
    case file_type::block: return "a block device";
    case file_type::character: return "a character device";
    case file_type::fifo: return "a FIFO";
    case file_type::socket: return "a socket";
    default: return "not a regular file";
  }
}

}  // namespace

void require_regular_output(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::symlink_status(path, ec);
  if (ec || status.type() == std::filesystem::file_type::not_found ||
      status.type() == std::filesystem::file_type::regular)
    return;
  throw InvalidInput(fmt::format("{}: is {}; frictopt writes regular files only and neither replaces nor writes "
                                 "through it (remove it or choose another output path)",
                                 path.string(), kind_of(status)));
}

std::filesystem::path make_sibling_temporary(const std::filesystem::path& path) {
  require_regular_output(path);
  const std::filesystem::path parent = path.parent_path().empty() ? "." : path.parent_path();
  std::string pattern = (parent / ("." + path.filename().string() + ".XXXXXX.tmp")).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkstemps(name.data(), 4);  // O_EXCL: never an existing file
  if (fd < 0) {
    const int error = errno;
    throw FileSystemError(fmt::format("cannot write '{}': {} (does its directory exist and is it writable?)",
                                      path.string(), std::strerror(error)),
                          path, error);
  }
  // mkstemp creates mode 0600; an output file gets the usual 0666 minus the umask (umask has
  // no read-only query, hence set and restore).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  ::close(fd);
  return std::filesystem::path(name.data());
}

void publish_file(const std::filesystem::path& temporary, const std::filesystem::path& path) {
  std::error_code ec;
  try {
    require_regular_output(path);  // again: the target may have appeared while we wrote
  } catch (...) {
    std::filesystem::remove(temporary, ec);
    throw;
  }
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    const std::string reason = ec.message();
    const int error = ec.value();
    std::filesystem::remove(temporary, ec);
    throw FileSystemError(fmt::format("cannot replace '{}': {}; the previous file is kept", path.string(), reason),
                          path, error);
  }
}

void write_all(int fd, std::string_view content, const std::filesystem::path& target) {
  std::size_t written = 0;
  while (written < content.size()) {
    const ssize_t n = ::write(fd, content.data() + written, content.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      // n == 0 with bytes left: a short write the system gave no reason for (a full device).
      const int error = n < 0 ? errno : ENOSPC;
      throw FileSystemError(fmt::format("writing '{}' failed after {} of {} bytes: {}", target.string(), written,
                                        content.size(), std::strerror(error)),
                            target, error);
    }
    written += static_cast<std::size_t>(n);
  }
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  const std::filesystem::path temporary = make_sibling_temporary(path);
  std::error_code ec;
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    std::filesystem::remove(temporary, ec);
    throw FileSystemError(fmt::format("writing '{}' failed: {}", path.string(), std::strerror(error)), path, error);
  }
  try {
    write_all(fd, content, path);
  } catch (...) {
    ::close(fd);
    std::filesystem::remove(temporary, ec);  // the previous file at `path` is untouched
    throw;
  }
  // close reports the errors of a write the system deferred (NFS, quotas): the file is then
  // incomplete and is not published.
  if (::close(fd) != 0) {
    const int error = errno;
    std::filesystem::remove(temporary, ec);
    throw FileSystemError(fmt::format("writing '{}' failed when closing it: {}; the previous file is kept",
                                      path.string(), std::strerror(error)),
                          path, error);
  }
  publish_file(temporary, path);
}

}  // namespace frictopt::io::detail
