// SPDX-License-Identifier: MIT
// frictopt.Case: a validated case from a TOML file or text (io::load_case / io::parse_case),
// the same parser, checks and messages as the case files of the CLI (docs/case-format.md).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "bindings.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/cost/cost_kind.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/mesh/gmsh_mesh.hpp"

namespace frictopt::python {

namespace {

// trust_geo = True for the duration of one case read (docs/meshes.md, "A .geo file runs no code").
class TrustGeo {
 public:
  explicit TrustGeo(bool trust) : before_(mesh::trust_geo_by_default()) { mesh::set_trust_geo_by_default(trust); }
  TrustGeo(const TrustGeo&) = delete;
  TrustGeo& operator=(const TrustGeo&) = delete;
  ~TrustGeo() { mesh::set_trust_geo_by_default(before_); }

 private:
  bool before_;
};

std::shared_ptr<Case> case_from_text(const std::string& text, const std::string& origin, bool trust_geo) {
  const TrustGeo trust(trust_geo);
  auto c = std::make_shared<Case>();
  c->description = io::parse_case(text, origin);
  c->toml = text;
  return c;
}

std::shared_ptr<Case> case_from_file(const std::filesystem::path& path, bool trust_geo) {
  const TrustGeo trust(trust_geo);
  auto c = std::make_shared<Case>();
  c->description = io::load_case(path);  // throws InvalidInput naming the file if unreadable
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  c->toml = text.str();
  return c;
}

}  // namespace

void bind_case(py::module_& m) {
  py::class_<Case, std::shared_ptr<Case>>(m, "Case", R"doc(
A validated frictopt case: body, material, loads, design and admissible set, friction law,
cost, optimization and identification settings (docs/case-format.md).

Create one with ``frictopt.load_case(path)``, ``frictopt.parse_case(text)`` or
``frictopt.Case.from_dict(tables)``; derive variants with ``case.with_overrides(...)``. Every
route goes through the case-file parser, so an invalid field raises ValueError with the same
message as the CLI, e.g. ``"case.toml:7: material.poisson = 0.6; expected 0 <= poisson < 0.5"``.
All quantities are SI: lengths in m, Young's modulus in Pa, displacements in m.
)doc")
      .def_static("from_file", &case_from_file, py::arg("path"), py::arg("trust_geo") = false,
                  "Reads and validates a TOML case file (same as ``frictopt.load_case``).")
      .def_static("from_toml", &case_from_text, py::arg("text"), py::arg("origin") = "<python>",
                  py::arg("trust_geo") = false,
                  "Parses and validates TOML text; ``origin`` prefixes every error message and its stem is\n"
                  "the default output name; relative paths in the case resolve against its directory.")
      .def_property_readonly("origin", [](const Case& c) { return c.description.origin; },
                             "Where the case came from (file path or origin name).")
      .def_property_readonly("toml", [](const Case& c) { return c.toml; }, "The TOML text of the case.")
      .def_property_readonly("name", [](const Case& c) { return c.description.body.name; },
                             "Base name of output files ([output].name, default the file stem).")
      .def_property_readonly("dim", [](const Case& c) { return c.description.dim(); }, "2 or 3.")
      .def_property_readonly("num_design_variables",
                             [](const Case& c) { return case_initial_design(c.description).size(); },
                             "Number of design variables: the Bézier control heights α (+ 1 with [design] friction_orientation).")
      .def_property_readonly("initial_design", [](const Case& c) { return to_numpy(case_initial_design(c.description)); },
                             "x⁰: α⁰, the initial control heights [m] (and s⁰ = kφ⁰ last with friction_orientation).")
      .def_property_readonly("young", [](const Case& c) { return c.description.body.material.young; },
                             "Young's modulus E [Pa].")
      .def_property_readonly("poisson", [](const Case& c) { return c.description.body.material.poisson; },
                             "Poisson's ratio ν [-].")
      .def_property_readonly(
          "friction_law",
          [](const Case& c) -> py::object {
            if (!c.description.body.contact) return py::none();
            return py::cast(c.description.body.contact->law);
          },
          "The friction law of [contact.friction] (a FrictionLaw), or None without contact.")
      .def_property_readonly(
          "cost_kind",
          [](const Case& c) -> py::object {
            if (!c.description.cost) return py::none();
            return py::str(std::string(cost::to_string(c.description.cost->kind)));
          },
          "The [cost] kind (e.g. 'target_pressure'), or None when the case has no cost.")
      .def_property_readonly("has_identification", [](const Case& c) { return c.description.identification.has_value(); },
                             "Whether the case has an [identification] table.")
      .def_property_readonly(
          "measurements_path",
          [](const Case& c) -> py::object {
            // The file of the case's own loads; [[identification.experiment]] tables name one each.
            if (!c.description.identification || c.description.identification->explicit_experiments) return py::none();
            const auto& file = c.description.identification->experiments.front().measurements;
            return file ? py::cast(*file) : py::none();
          },
          "The measurement CSV of [identification] (resolved against the case's directory), or None (no file, or\n"
          "[[identification.experiment]] tables, each with its own measurements).")
      .def("__repr__", [](const Case& c) {
        const auto& b = c.description.body;
        return fmt::format("<frictopt.Case '{}' from {}: {}D, {} design variables, friction {}, cost {}>", b.name,
                           c.description.origin, c.description.dim(), case_initial_design(c.description).size(),
                           b.contact ? b.contact->law.describe() : std::string("none"),
                           c.description.cost ? std::string(cost::to_string(c.description.cost->kind)) : "none");
      });

  m.def("load_case", &case_from_file, py::arg("path"), py::arg("trust_geo") = false,
        "Reads and validates a TOML case file; raises ValueError naming file, field, value and\n"
        "expectation on bad input (the CLI's messages). A [mesh] file that is a .geo is read\n"
        "restricted (no shell, no file writes, no Exit; docs/meshes.md); ``trust_geo=True`` runs it\n"
        "with every Gmsh command, only for a file you have read and trust.");
  m.def("parse_case", &case_from_text, py::arg("text"), py::arg("origin") = "<python>", py::arg("trust_geo") = false,
        "Parses and validates the TOML text of a case; ``origin`` prefixes error messages\n"
        "(e.g. a path, so that relative paths in the case resolve against its directory).");
}

}  // namespace frictopt::python
