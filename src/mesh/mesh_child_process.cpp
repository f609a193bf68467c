// SPDX-License-Identifier: MIT
#include "mesh_child_process.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <exception>
#include <new>
#include <system_error>

#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "frictopt/core/error.hpp"

namespace frictopt::mesh::detail {
namespace {

// The message kinds of the child's answer: its first byte.
constexpr char kOk = 'O';
constexpr char kInvalid = 'E';
constexpr char kFailed = 'X';

bool write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

// The caller's address space now [bytes] (the limit of the child adds to it).
std::uint64_t address_space_bytes() {
  FILE* f = std::fopen("/proc/self/statm", "r");
  if (f == nullptr) return 0;
  unsigned long long pages = 0;
  const int read = std::fscanf(f, "%llu", &pages);
  std::fclose(f);
  return read == 1 ? pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE)) : 0;
}

[[noreturn]] void child_main(int fd, const ChildLimits& limits, std::uint64_t base, const std::function<std::string()>& work) {
  // No core file of a Gmsh crash in the user's folder; no output into the caller's streams.
  const rlimit no_core{0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
  if (limits.memory_bytes > 0 && base > 0) {
    const rlimit as{base + limits.memory_bytes, base + limits.memory_bytes};
    ::setrlimit(RLIMIT_AS, &as);
  }
  if (const int null = ::open("/dev/null", O_WRONLY); null >= 0) {
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    ::close(null);
  }
  std::string answer;
  try {
    answer = kOk + work();
  } catch (const InvalidInput& e) {
    answer = std::string(1, kInvalid) + e.what();
  } catch (const std::bad_alloc&) {
    answer = std::string(1, kFailed) + fmt::format("ran out of memory at its limit of {:.2g} GB ({}); expected a "
                                                   "mesh within the limit (coarser sizes in the .geo or the case)",
                                                   static_cast<double>(limits.memory_bytes) / 1e9, limits.memory_hint);
  } catch (const std::exception& e) {
    answer = std::string(1, kFailed) + e.what();
  } catch (...) {
    answer = std::string(1, kFailed) + "failed with an exception of unknown type";
  }
  const bool ok = write_all(fd, answer.data(), answer.size());
  ::close(fd);
  ::_exit(ok ? 0 : 1);  // no atexit handlers, no flush of the caller's buffers
}

}  // namespace

std::string run_in_child(const std::string& what, const ChildLimits& limits, const std::function<std::string()>& work) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw std::system_error(errno, std::generic_category(), "pipe for the Gmsh child");
  const std::uint64_t base = address_space_bytes();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::system_error(error, std::generic_category(), "fork of the Gmsh child");
  }
  if (pid == 0) {
    ::close(fds[0]);
    child_main(fds[1], limits, base, work);
  }
  ::close(fds[1]);
  std::string answer;
  bool timed_out = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limits.seconds);
  char buffer[1 << 16];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of the answer (or the child is gone)
    answer.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  if (timed_out) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (timed_out)
    throw InvalidInput(fmt::format("{}: Gmsh did not finish within {:g} s and was stopped; expected a file Gmsh reads "
                                   "and meshes in that time (a coarser mesh, fewer loop iterations)",
                                   what, limits.seconds));
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    const char* name = ::sigabbrev_np(signal);
    throw InvalidInput(fmt::format("{}: Gmsh crashed (signal {}{}{}) while reading or meshing it; expected a file "
                                   "Gmsh can read (docs/meshes.md lists the known crashes of Gmsh 4.8; an allocation "
                                   "beyond the child's memory limit of {:.2g} GB ends so too: {})",
                                   what, signal, name != nullptr ? " SIG" : "", name != nullptr ? name : "",
                                   static_cast<double>(limits.memory_bytes) / 1e9, limits.memory_hint));
  }
  if (answer.empty())
    throw InvalidInput(fmt::format("{}: Gmsh ended the process (exit status {}) without a mesh; expected a file that "
                                   "does not end Gmsh (an Exit command, an error of Gmsh)",
                                   what, WIFEXITED(status) ? WEXITSTATUS(status) : -1));
  const char kind = answer[0];
  answer.erase(0, 1);
  if (kind == kOk) return answer;
  if (kind == kInvalid) throw InvalidInput(answer);
  throw InvalidInput(fmt::format("{}: Gmsh {}", what, answer));
}

}  // namespace frictopt::mesh::detail
