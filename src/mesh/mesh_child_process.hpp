// SPDX-License-Identifier: MIT
// Running Gmsh in a forked child process (docs/meshes.md, "Gmsh in a child process"). Private
// to the mesh module.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace frictopt::mesh::detail {

struct ChildLimits {
  double seconds = 600.0;           ///< wall clock; then the child is killed
  std::uint64_t memory_bytes = 0;   ///< added to the caller's address space; 0: no limit
  std::string memory_hint;          ///< why memory_bytes, for the message of a failed allocation
};

/// Runs `work` in a child process (fork) and returns the bytes it returned. The child's stdout
/// and stderr go to /dev/null and it writes no core file. An InvalidInput thrown by `work` is
/// thrown again here with its message; any other way the child ends — a signal (Gmsh's
/// SIGSEGV), an exit of its own (a .geo's Exit), another exception, the time limit — becomes
/// an InvalidInput that begins with `what` and says how the child ended. A failed fork or pipe
/// is a std::system_error.
std::string run_in_child(const std::string& what, const ChildLimits& limits, const std::function<std::string()>& work);

}  // namespace frictopt::mesh::detail
