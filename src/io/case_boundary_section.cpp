// SPDX-License-Identifier: MIT
#include "case_boundary_section.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "case_mesh_section.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::io::detail {
namespace {

// A traction above Young's modulus means a strain above 1: outside linear elasticity.
// The part of the boundary a [[load]] or [[dirichlet]] table names: `face` on the structured
// box, `boundary` (a physical group) on an imported body (docs/meshes.md; null: the box).
std::string read_part(const TableReader& r, int dim, const mesh::Mesh* imported) {
  const std::string_view other = imported ? "face" : "boundary";
  if (r.has(other))
    r.fail(other, fmt::format("{} is for {}; this case's body {}", r.field(other),
                              imported ? "the structured box" : "a body imported from a mesh file ([mesh] file)",
                              imported ? "comes from [mesh] file: name a physical group with boundary = \"...\""
                                       : "is the structured box: name a face with face = \"...\""));
  return imported ? detail::read_boundary_group(r, *imported) : read_face(r, dim);
}

fem::FaceTraction read_load(const TableReader& r, int dim, double young, const mesh::Mesh* imported) {
  fem::FaceTraction load;
  load.boundary = read_part(r, dim, imported);
  load.traction = read_dim_vector(r, "traction", dim, "traction, N/m²");
  for (Eigen::Index i = 0; i < dim; ++i)
    if (!(std::abs(load.traction(i)) <= young))
      r.fail_entry("traction", static_cast<std::size_t>(i),
                   fmt::format("|traction| <= material.young = {} Pa (a larger traction strains the body by more "
                               "than 100%, outside linear elasticity)",
                               young));
  return load;
}

// A prescribed displacement larger than the body is outside small-strain elasticity.
fem::FaceDirichlet read_dirichlet(const TableReader& r, int dim, double body_size, const mesh::Mesh* imported) {
  fem::FaceDirichlet d;
  d.boundary = read_part(r, dim, imported);
  d.displacement = r.has("displacement")
                       ? read_dim_vector(r, "displacement", dim, "displacement, m")
                       : Eigen::VectorXd::Zero(dim);
  for (Eigen::Index i = 0; i < dim; ++i)
    if (!(std::abs(d.displacement(i)) <= body_size))
      r.fail_entry("displacement", static_cast<std::size_t>(i),
                   fmt::format("|displacement| <= {} m, the largest side of the body (small-strain elasticity)",
                               body_size));
  if (r.has("components")) {
    const std::string what = fmt::format(
        "a non-empty list of distinct component indices in "
        "0..{}",
        dim - 1);
    d.components = r.int_list("components", what);
    if (d.components.empty()) r.fail_value("components", what);
    for (std::size_t i = 0; i < d.components.size(); ++i) {
      if (d.components[i] < 0 || d.components[i] >= dim)
        r.fail_entry("components", i,
                     fmt::format("an index in 0..{} in {}", dim - 1, dim_name(dim)));
      for (std::size_t j = 0; j < i; ++j)
        if (d.components[j] == d.components[i])
          r.fail_entry("components", i,
                       fmt::format("distinct indices, but it repeats "
                                   "components[{}]",
                                   j));
    }
    std::sort(d.components.begin(), d.components.end());
  } else {
    for (int c = 0; c < dim; ++c) d.components.push_back(c);
  }
  return d;
}

// A traction component on a face that a [[dirichlet]] table fixes in that component does no
// work (the reaction absorbs it): it is always a mistake in the case, so it is refused.
void check_loads_on_fixed_faces(const CaseDescription& c, int dim,
                                const BoundaryFixings& fixed_by) {
  const std::vector<fem::FaceTraction>& loads = c.body.tractions;
  for (std::size_t i = 0; i < loads.size(); ++i) {
    const fem::FaceTraction& load = loads[i];
    for (int comp = 0; comp < dim; ++comp) {
      const auto it = fixed_by.find({load.boundary, comp});
      if (load.traction(comp) != 0.0 && it != fixed_by.end())
        throw InvalidInput(fmt::format(
            "{}: load[{}].traction[{}] = {} acts on face \"{}\" in component {}, which dirichlet[{}] fixes on the "
            "same face, so the load does no work; expected a traction on free components only (remove the load, "
            "set that component to 0, or free it)",
            c.origin, i, comp, load.traction(comp), load.boundary, comp, it->second));
    }
  }
}


}  // namespace

BoundaryFixings read_boundary_sections(const TableReader& top, std::string_view origin, const Geometry& geometry,
                                       const mesh::Mesh* imported_mesh, CaseDescription& c) {
  study::BodyDefinition& body = c.body;
  const int dim = geometry.dim;
  if (const toml::array* loads = top.optional_table_array("load", kMaxBodyTables))
    for (std::size_t i = 0; i < loads->size(); ++i)
      body.tractions.push_back(
          read_load(TableReader(*loads->get(i)->as_table(), fmt::format("load[{}]", i), origin,
                                {"face", "boundary", "traction"}),
                    dim, body.material.young, imported_mesh));

  const toml::array* dirichlet = top.optional_table_array("dirichlet", kMaxBodyTables);
  // Without [[dirichlet]] a body floats: only contact and friction can hold it
  // (docs/experiments.md §5; study::ElasticBody solves it with the kernel-aware dual).
  const toml::array no_dirichlet;
  if ((dirichlet == nullptr || dirichlet->empty()) && top.optional_table("contact") == nullptr &&
      top.optional_table_array("constraint", kMaxBodyTables) == nullptr)
    top.fail_missing("dirichlet",
                     "at least one [[dirichlet]] table (a body without a "
                     "Dirichlet part and without [contact] has rigid-body modes)");
  if (dirichlet == nullptr) dirichlet = &no_dirichlet;
  // (face, component) -> index of the [[dirichlet]] entry that fixes it first.
  BoundaryFixings fixed_by;
  for (std::size_t i = 0; i < dirichlet->size(); ++i) {
    const TableReader r(*dirichlet->get(i)->as_table(), fmt::format("dirichlet[{}]", i), origin,
                        {"face", "boundary", "displacement", "components"});
    fem::FaceDirichlet d =
        read_dirichlet(r, dim, std::max({geometry.a, geometry.b, geometry.height}), imported_mesh);
    for (int comp : d.components) {
      const auto [it, inserted] = fixed_by.emplace(std::pair{d.boundary, comp}, i);
      if (!inserted)
        r.fail("face", fmt::format("{}.face = \"{}\" fixes component {}, which dirichlet[{}] "
                                   "already fixes on the same face; expected each component "
                                   "of a face fixed at most once",
                                   r.path(), d.boundary, comp, it->second));
    }
    body.dirichlet.push_back(std::move(d));
  }

  check_loads_on_fixed_faces(c, dim, fixed_by);
  return fixed_by;
}

// With contact, the unknowns above the contact surface form the leading block of the
// stiffness (contact unknowns are ordered last, docs/contact.md): with one cell layer and a
// fully fixed top that block is empty and there is no elastic body left to solve for.
void check_free_unknowns(const CaseDescription& c, int dim,
                         const BoundaryFixings& fixed_by) {
  if (!c.body.contact) return;
  const auto& [n1, n2, nv] = c.body.resolution.cells;  // n2 = 0 in 2D
  std::int64_t free_unknowns = 0;
  for (int k = 1; k <= nv && free_unknowns == 0; ++k)
    for (int i2 = 0; i2 <= n2 && free_unknowns == 0; ++i2)
      for (int i1 = 0; i1 <= n1; ++i1) {
        std::vector<std::string> faces;  // the structured grid's boundary sets holding this node
        if (i1 == 0) faces.push_back("left");
        if (i1 == n1) faces.push_back("right");
        if (dim == 3 && i2 == 0) faces.push_back("front");
        if (dim == 3 && i2 == n2) faces.push_back("back");
        if (k == nv) faces.push_back("top");
        for (int comp = 0; comp < dim; ++comp)
          if (std::none_of(faces.begin(), faces.end(),
                           [&](const std::string& f) { return fixed_by.count({f, comp}) > 0; }))
            ++free_unknowns;
        if (free_unknowns > 0) break;
      }
  if (free_unknowns == 0) {
    const std::string cells = dim == 2 ? fmt::format("{}, {}", n1, nv) : fmt::format("{}, {}, {}", n1, n2, nv);
    throw InvalidInput(fmt::format(
        "{}: mesh.cells = [{}] with the [[dirichlet]] tables fixes every unknown above the contact surface: the body "
        "has no free unknown left but the contact ones; expected at least 2 cell layers (mesh.cells[{}] >= 2) or a "
        "top face that is not fixed in every component",
        c.origin, cells, dim - 1));
  }
}

}  // namespace frictopt::io::detail
