// SPDX-License-Identifier: MIT
#include "child_process.hpp"

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "frictopt/io/file_error.hpp"
#include "input_file.hpp"

namespace frictopt::io::detail {

ChildResult run_in_child(const std::function<int()>& work) {
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0)
    throw FileSystemError(fmt::format("cannot create a pipe: {}", std::strerror(errno)), {}, errno);
  // Whatever the parent buffered must not be written twice (by the child's exit()).
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    throw FileSystemError(fmt::format("cannot start a child process: {}", std::strerror(error)), {}, error);
  }
  if (pid == 0) {
    ::close(pipe_fds[0]);
    ::dup2(pipe_fds[1], STDERR_FILENO);
    ::close(pipe_fds[1]);
    int code = 1;
    try {
      code = work();
    } catch (...) {
      code = 1;
    }
    std::fflush(stderr);
    ::_exit(code);  // no atexit handlers of the parent's, no second flush of its buffers
  }
  ::close(pipe_fds[1]);
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(pipe_fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
    if (text.size() > 65536) text.erase(0, text.size() - 65536);  // keep the end
  }
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  ChildResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 1;
  // The most telling part of an HDF5 error stack is its last lines ("No space left on device").
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  std::size_t start = text.size();
  for (int lines = 0; lines < 3 && start > 0; ++lines) {
    const std::size_t nl = text.rfind('\n', start - 1);
    start = nl == std::string::npos ? 0 : nl;
    if (nl == std::string::npos) break;
  }
  std::string tail = text.substr(start);
  for (char& ch : tail)
    if (ch == '\n') ch = ' ';
  result.diagnostics = printable_excerpt(tail, 400);
  return result;
}

}  // namespace frictopt::io::detail
