// SPDX-License-Identifier: MIT
// Runs a piece of work that may end the process (a library that calls exit() on an error, such
// as fclib on a failed HDF5 call) in a forked child, so that its failure becomes a result.
#pragma once

#include <functional>
#include <string>

namespace frictopt::io::detail {

struct ChildResult {
  int exit_code = 0;        ///< the work's return value; its exit status; 128 + signal if killed
  std::string diagnostics;  ///< the last lines the child wrote to stderr (bounded, printable)
};

/// Forks, runs `work` in the child (its return value is the child's exit status; stderr goes to
/// a pipe) and waits for it. The child shares nothing back but the files it wrote. Throws
/// FileSystemError if the system cannot fork.
[[nodiscard]] ChildResult run_in_child(const std::function<int()>& work);

}  // namespace frictopt::io::detail
