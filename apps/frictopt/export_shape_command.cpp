// SPDX-License-Identifier: MIT
// `frictopt export-shape`: see apps/frictopt/commands.hpp.
#include <fmt/format.h>

#include "commands.hpp"
#include "frictopt/io/shape_export.hpp"

namespace frictopt::app {

int run_export_shape(const std::filesystem::path& run_dir, const std::filesystem::path& design_path) {
  const io::ShapeExport e = io::export_shape(run_dir, design_path);
  if (e.surface.geometry)
    fmt::print("design patch: Bézier {} of {}×{} control points; it meets the designed mesh to {:.3e} m ({:.1e} of "
               "its size)\n",
               e.surface.geometry->m2 > 1 ? "surface" : "curve", e.surface.geometry->m1, e.surface.geometry->m2,
               e.surface.max_node_deviation, e.surface.max_node_deviation / e.surface.size);
  for (const std::string& note : e.notes) fmt::print("note: {}\n", note);
  for (const auto& file : e.files) fmt::print("wrote {}\n", file.string());
  return kExitOk;
}

}  // namespace frictopt::app
