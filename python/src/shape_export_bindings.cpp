// SPDX-License-Identifier: MIT
// frictopt.export_shape: a run's design out as STEP, .msh and STL (io::export_shape, the same
// files as `frictopt export-shape`).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "frictopt/io/shape_export.hpp"

namespace frictopt::python {

void bind_shape_export(py::module_& m) {
  m.def(
      "export_shape",
      [](const std::filesystem::path& run_directory, const py::object& design) {
        const std::filesystem::path design_file =
            design.is_none() ? std::filesystem::path{} : design.cast<std::filesystem::path>();
        io::ShapeExport e;
        {
          py::gil_scoped_release release;
          e = io::export_shape(run_directory, design_file);
        }
        py::dict out;
        py::list files;
        for (const auto& f : e.files) files.append(py::cast(f));
        out["files"] = files;
        out["notes"] = py::cast(e.notes);
        if (e.surface.geometry) {
          out["control_points"] = to_numpy(e.surface.geometry->points);
          out["net"] = py::make_tuple(e.surface.geometry->m1, e.surface.geometry->m2);
        } else {
          out["control_points"] = py::none();
          out["net"] = py::none();
        }
        out["max_node_deviation"] = e.surface.max_node_deviation;
        out["patch_size"] = e.surface.size;
        return py::module_::import("frictopt._summary").attr("Summary")(out);
      },
      py::arg("run_directory"), py::arg("design") = py::none(),
      R"doc(Writes a run's design out, as ``frictopt export-shape`` (docs/meshes.md, "The optimized
shape out"): NAME_design.step (the design patch as an exact Bézier/B-spline surface in 3D, a curve
in 2D, lengths in millimetres), NAME_optimized.msh (the body at the design, Gmsh MSH 4.1 with the
boundary sets as named physical groups, metres) and in 3D NAME_optimized.stl (its exterior).

run_directory: a run written by ``optimize`` (its case.toml and final_design.json).
design: a design JSON to export instead of final_design.json.

Returns a Summary: files (the paths written), notes (what was not written and why, e.g. a patch
that is not plane in the reference), control_points ((m1·m2) × 3 array [m], row i + m1·j, or
None), net ((m1, m2) or None), max_node_deviation [m] (the surface against the designed patch
nodes) and patch_size [m].)doc");
}

}  // namespace frictopt::python
