// SPDX-License-Identifier: MIT
#include "input_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>

#include "frictopt/core/error.hpp"
#include "frictopt/io/file_error.hpp"

namespace frictopt::io::detail {
namespace {

std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  [[nodiscard]] int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

std::string read_input_file(const std::filesystem::path& path, std::string_view what, std::size_t max_bytes) {
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer.
  const Descriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY));
  if (fd.get() < 0) {
    const int error = errno;
    if (error == ENOENT || error == ENOTDIR)
      throw InvalidInput(fmt::format("{}: {} not found (no such file)", path.string(), what));
    throw FileSystemError(fmt::format("{}: cannot read {}: {}", path.string(), what, std::strerror(error)), path,
                          error);
  }
  struct stat info {};
  if (::fstat(fd.get(), &info) != 0)
    throw FileSystemError(fmt::format("{}: cannot read {}: {}", path.string(), what, std::strerror(errno)), path, errno);
  if (!S_ISREG(info.st_mode))
    throw InvalidInput(fmt::format("{}: {} is {}; expected a regular file", path.string(), what, kind_of(info.st_mode)));
  if (static_cast<std::uint64_t>(info.st_size) > max_bytes)
    throw InvalidInput(fmt::format("{}: {} has {} bytes; expected at most {} (not a file frictopt wrote?)",
                                   path.string(), what, info.st_size, max_bytes));
  // Blocking reads from here on (a regular file never blocks; O_NONBLOCK is for the open only).
  const int flags = ::fcntl(fd.get(), F_GETFL);
  if (flags >= 0) ::fcntl(fd.get(), F_SETFL, flags & ~O_NONBLOCK);
  std::string text;
  text.resize(static_cast<std::size_t>(info.st_size));
  std::size_t done = 0;
  for (;;) {
    if (done == text.size()) {
      if (text.size() >= max_bytes + 1) break;
      text.resize(std::min(max_bytes + 1, text.size() + 4096));  // the file may have grown
    }
    const ssize_t n = ::read(fd.get(), text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0)
      throw FileSystemError(fmt::format("{}: reading {} failed: {}", path.string(), what, std::strerror(errno)), path,
                            errno);
    if (n == 0) break;
    done += static_cast<std::size_t>(n);
  }
  if (done > max_bytes)
    throw InvalidInput(fmt::format("{}: {} has more than {} bytes; expected at most that (not a file frictopt wrote?)",
                                   path.string(), what, max_bytes));
  text.resize(done);
  return text;
}

std::string printable_excerpt(std::string_view text, std::size_t max_chars) {
  std::string out;
  for (char ch : text.substr(0, max_chars)) {
    const auto c = static_cast<unsigned char>(ch);
    out += c >= 0x20 && c < 0x7f ? ch : '?';
  }
  if (text.size() > max_chars) out += "...";
  return out;
}

}  // namespace frictopt::io::detail
