// SPDX-License-Identifier: MIT
#include "case_plate_section.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "case_mesh_section.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/mesh/face.hpp"

namespace frictopt::io::detail {
namespace {

std::string directions_for(int dim) { return dim == 2 ? "\"x\", \"y\"" : "\"x\", \"y\", \"z\""; }

// A list of direction names ("x", "y", "z"), each at most once; sorted indices.
std::vector<int> read_directions(const TableReader& r, std::string_view key, int dim) {
  const std::string what = fmt::format("a list of distinct directions among {}", directions_for(dim));
  const toml::array* list = r.node(key)->as_array();
  if (list == nullptr) r.fail_value(key, what);
  std::vector<int> out;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const auto* s = list->get(i)->as_string();
    int c = -1;
    if (s != nullptr) {
      const std::string& text = s->get();
      if (text == "x") c = 0;
      else if (text == "y") c = 1;
      else if (text == "z" && dim == 3) c = 2;
    }
    if (c < 0) r.fail_entry(key, i, fmt::format("one of {} ({}D body)", directions_for(dim), dim));
    if (std::find(out.begin(), out.end(), c) != out.end())
      r.fail_entry(key, i, fmt::format("a direction not already listed in {}", r.field(key)));
    out.push_back(c);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string read_plate_part(const TableReader& r, int dim, const mesh::Mesh* imported) {
  if (imported) {
    if (r.has("face"))
      r.fail("face", fmt::format("{}: the body comes from [mesh] file; expected boundary = \"...\" naming one of its "
                                 "physical groups",
                                 r.field("face")));
    return read_boundary_group(r, *imported);
  }
  if (r.has("boundary"))
    r.fail("boundary", fmt::format("{}: the body is the structured box; expected face = \"...\" ({})", r.field("boundary"),
                                   dim == 2 ? "left, right, top" : "left, right, front, back, top"));
  const std::string faces = dim == 2 ? "left, right, top" : "left, right, front, back, top";
  const std::string text = r.required_string("face", fmt::format("one of {}", faces));
  std::optional<mesh::Face> face;
  try {
    face = mesh::parse_face(text);
  } catch (const InvalidInput&) {
  }
  if (!face || *face == mesh::Face::kBottom || (dim == 2 && (*face == mesh::Face::kFront || *face == mesh::Face::kBack)))
    r.fail_value("face", fmt::format("one of {} (the bottom is the contact surface)", faces));
  return std::string(mesh::to_string(*face));
}

}  // namespace

void read_plate_sections(const TableReader& top, std::string_view origin, int dim, const mesh::Mesh* imported,
                         CaseDescription& c) {
  const toml::array* plates = top.optional_table_array("plate", kMaxBodyTables);
  if (plates == nullptr) return;
  for (std::size_t i = 0; i < plates->size(); ++i) {
    const std::string path = fmt::format("plate[{}]", i);
    const TableReader r(*plates->get(i)->as_table(), path, origin, {"face", "boundary", "force", "tied", "held"});
    fem::LoadingPlate plate;
    plate.boundary = read_plate_part(r, dim, imported);
    plate.field = fmt::format("{}: {}", origin, path);
    const std::string force_what = fmt::format("a list of {} finite numbers (the plate's total force [N] in x, y{})",
                                               dim, dim == 3 ? ", z" : "");
    const std::vector<double> force = r.number_list("force", force_what);
    if (static_cast<int>(force.size()) != dim) r.fail_value("force", force_what);
    for (std::size_t k = 0; k < force.size(); ++k)
      if (!std::isfinite(force[k])) r.fail_entry("force", k, "a finite number [N]");
    plate.force = Eigen::Map<const Eigen::VectorXd>(force.data(), dim);
    if (r.has("held")) plate.held = read_directions(r, "held", dim);
    if (r.has("tied")) {
      plate.tied = read_directions(r, "tied", dim);
    } else {
      for (int k = 0; k < dim; ++k)
        if (std::find(plate.held.begin(), plate.held.end(), k) == plate.held.end()) plate.tied.push_back(k);
    }
    for (int k : plate.held)
      if (std::find(plate.tied.begin(), plate.tied.end(), k) != plate.tied.end())
        r.fail("held", fmt::format("{}: direction \"{}\" is both held and tied (force-driven); expected each direction in "
                                   "at most one of the two lists",
                                   r.path(), fem::direction_name(k)));
    if (plate.tied.empty() && plate.held.empty())
      r.fail("tied", fmt::format("{}: no tied and no held direction; expected at least one", r.path()));
    for (int k = 0; k < dim; ++k)
      if (plate.force(k) != 0.0 && std::find(plate.tied.begin(), plate.tied.end(), k) == plate.tied.end())
        r.fail("force", fmt::format("{}.force[{}] = {} N in direction \"{}\", which the plate {}; expected 0 there (a "
                                    "force drives a tied direction only)",
                                    r.path(), k, plate.force(k), fem::direction_name(k),
                                    std::find(plate.held.begin(), plate.held.end(), k) != plate.held.end()
                                        ? "holds at zero displacement"
                                        : "does not tie"));
    for (std::size_t j = 0; j < c.body.plates.size(); ++j)
      if (c.body.plates[j].boundary == plate.boundary)
        r.fail(imported ? "boundary" : "face",
               fmt::format("{}: \"{}\" is already the part of plate[{}]; expected one plate per part", r.path(),
                           plate.boundary, j));
    // The same face (or group) fixed by a [[dirichlet]] table in a direction the plate acts in.
    for (std::size_t j = 0; j < c.body.dirichlet.size(); ++j) {
      const fem::FaceDirichlet& d = c.body.dirichlet[j];
      if (d.boundary != plate.boundary) continue;
      for (int k = 0; k < dim; ++k) {
        const bool fixed = d.components.empty() || std::find(d.components.begin(), d.components.end(), k) != d.components.end();
        const bool acts = std::find(plate.tied.begin(), plate.tied.end(), k) != plate.tied.end() ||
                          std::find(plate.held.begin(), plate.held.end(), k) != plate.held.end();
        if (fixed && acts)
          r.fail(imported ? "boundary" : "face",
                 fmt::format("{}: \"{}\" is fixed in direction \"{}\" by dirichlet[{}]; expected a plate on a part no "
                             "[[dirichlet]] table fixes in the plate's directions (hold a direction with held = [...])",
                             r.path(), plate.boundary, fem::direction_name(k), j));
      }
    }
    c.body.plates.push_back(std::move(plate));
  }
}

}  // namespace frictopt::io::detail
