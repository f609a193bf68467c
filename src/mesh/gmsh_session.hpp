// SPDX-License-Identifier: MIT
// One Gmsh library session and the wrapper that turns Gmsh's failures into InvalidInput; shared
// by the Gmsh reader (gmsh_mesh.cpp) and the CAD export (cad_export.cpp). Private to the mesh
// module. Gmsh keeps one global model and is not thread-safe: both users open a session only
// inside the child process of run_in_child (mesh_child_process.hpp), so the parent never holds
// Gmsh state and concurrent uses are separate processes.
#pragma once

#include <fmt/format.h>
#include <gmsh.h>

#include <filesystem>
#include <new>
#include <string>
#include <string_view>

#include "frictopt/core/error.hpp"

namespace frictopt::mesh::detail {

/// gmsh::initialize … gmsh::finalize on every path, quiet (the child's stdout is /dev/null
/// anyway; errors are collected from Gmsh's logger into our messages).
class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 1);
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
  ~GmshSession() { gmsh::finalize(); }
};

/// Runs a Gmsh call; a failure (Gmsh throws objects of unspecified type) becomes InvalidInput
/// naming `file` and `what`, with Gmsh's last error message.
template <class F>
void gmsh_call(const std::filesystem::path& file, std::string_view what, F&& f) {
  try {
    f();
  } catch (const InvalidInput&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;  // the child's memory limit: reported with the limit by run_in_child
  } catch (...) {
    std::string error;
    try {
      gmsh::logger::getLastError(error);
    } catch (...) {
    }
    throw InvalidInput(fmt::format("{}: Gmsh could not {}: {}", file.string(), what,
                                   error.empty() ? "no message from Gmsh" : error));
  }
}

}  // namespace frictopt::mesh::detail
