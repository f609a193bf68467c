// SPDX-License-Identifier: MIT
#include "frictopt/fem/loading_plate.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "frictopt/core/error.hpp"

namespace frictopt::fem {

std::string direction_name(int c) {
  static const char* const names[] = {"x", "y", "z"};
  return c >= 0 && c < 3 ? names[c] : fmt::format("{}", c);
}

std::vector<std::vector<int>> plate_ties(const mesh::Mesh& mesh, const std::vector<LoadingPlate>& plates) {
  const int dim = mesh.dim();
  std::vector<std::vector<int>> ties;
  for (const LoadingPlate& plate : plates)
    for (int c : plate.tied) {
      std::vector<int> group;
      for (int node : mesh.boundary(plate.boundary).nodes) group.push_back(node * dim + c);
      ties.push_back(std::move(group));
    }
  return ties;
}

void add_plate_held_dofs(const mesh::Mesh& mesh, const std::vector<LoadingPlate>& plates, PrescribedDofs& prescribed) {
  const int dim = mesh.dim();
  for (const LoadingPlate& plate : plates)
    for (int c : plate.held)
      for (int node : mesh.boundary(plate.boundary).nodes) {
        prescribed.dofs.push_back(node * dim + c);
        prescribed.values.push_back(0.0);
      }
}

std::vector<NodalForce> plate_nodal_forces(const std::vector<LoadingPlate>& plates) {
  std::vector<NodalForce> forces;
  for (const LoadingPlate& plate : plates) {
    if (plate.force.isZero(0.0)) continue;
    NodalForce f;
    f.where.boundary = plate.boundary;
    f.force = plate.force;
    forces.push_back(std::move(f));
  }
  return forces;
}

void validate_plates(const mesh::Mesh& mesh, const std::vector<LoadingPlate>& plates, const PrescribedDofs& prescribed,
                     const std::string& contact_surface) {
  const int dim = mesh.dim();
  std::vector<char> fixed(static_cast<std::size_t>(mesh.num_dofs()), 0);
  for (int d : prescribed.dofs) fixed[static_cast<std::size_t>(d)] = 1;
  std::vector<int> owner(static_cast<std::size_t>(mesh.num_dofs()), -1);
  std::vector<char> contact(static_cast<std::size_t>(mesh.num_nodes()), 0);
  if (!contact_surface.empty() && mesh.has_boundary(contact_surface))
    for (int node : mesh.boundary(contact_surface).nodes) contact[static_cast<std::size_t>(node)] = 1;
  for (std::size_t p = 0; p < plates.size(); ++p) {
    const LoadingPlate& plate = plates[p];
    const std::string& field = plate.field;
    if (!mesh.has_boundary(plate.boundary))
      throw InvalidInput(fmt::format("{}: the mesh has no boundary part \"{}\"; expected one of {}", field,
                                     plate.boundary, fmt::join(mesh.boundary_names(), ", ")));
    if (plate.force.size() != dim || !plate.force.allFinite())
      throw InvalidInput(fmt::format("{}.force has {} entries; expected {} finite numbers (one per direction of the "
                                     "{}D body)",
                                     field, plate.force.size(), dim, dim));
    for (int c : plate.tied)
      if (c < 0 || c >= dim) throw InvalidInput(fmt::format("{}.tied: direction {} out of range; expected 0..{}", field, c, dim - 1));
    for (int c : plate.held) {
      if (c < 0 || c >= dim) throw InvalidInput(fmt::format("{}.held: direction {} out of range; expected 0..{}", field, c, dim - 1));
      if (std::find(plate.tied.begin(), plate.tied.end(), c) != plate.tied.end())
        throw InvalidInput(fmt::format("{}: direction {} is both held and tied (force-driven); expected one of the two",
                                       field, direction_name(c)));
    }
    if (plate.tied.empty() && plate.held.empty())
      throw InvalidInput(fmt::format("{}: no tied and no held direction; expected at least one", field));
    for (int c = 0; c < dim; ++c)
      if (plate.force(c) != 0.0 && std::find(plate.tied.begin(), plate.tied.end(), c) == plate.tied.end())
        throw InvalidInput(fmt::format(
            "{}.force[{}] = {:.6g} N in direction {}, which the plate {}; expected 0 (a force is carried by a tied, "
            "force-driven direction only)",
            field, c, plate.force(c), direction_name(c),
            std::find(plate.held.begin(), plate.held.end(), c) != plate.held.end() ? "holds" : "does not tie"));
    for (int node : mesh.boundary(plate.boundary).nodes) {
      if (contact[static_cast<std::size_t>(node)])
        throw InvalidInput(fmt::format("{}: boundary part \"{}\" shares node {} with the contact surface \"{}\"; expected "
                                       "a plate away from the contact surface",
                                       field, plate.boundary, node, contact_surface));
      for (int c = 0; c < dim; ++c) {
        const bool acts = std::find(plate.tied.begin(), plate.tied.end(), c) != plate.tied.end() ||
                          std::find(plate.held.begin(), plate.held.end(), c) != plate.held.end();
        if (!acts) continue;
        const auto dof = static_cast<std::size_t>(node * dim + c);
        if (fixed[dof])
          throw InvalidInput(fmt::format("{}: boundary part \"{}\" overlaps a Dirichlet condition at node {} in direction "
                                         "{}; expected a plate whose nodes no [[dirichlet]] or [[constraint]] fixes "
                                         "(hold a direction with {}.held instead)",
                                         field, plate.boundary, node, direction_name(c), field));
        if (owner[dof] >= 0)
          throw InvalidInput(fmt::format("{}: node {} in direction {} belongs to {} too; expected plates that share no "
                                         "node in a direction both act in",
                                         field, node, direction_name(c), plates[static_cast<std::size_t>(owner[dof])].field));
        owner[dof] = static_cast<int>(p);
      }
    }
  }
}

PlateReading read_plate(const mesh::Mesh& mesh, const LoadingPlate& plate,
                        const Eigen::Ref<const Eigen::VectorXd>& displacement,
                        const Eigen::Ref<const Eigen::VectorXd>& residual) {
  const int dim = mesh.dim();
  const std::vector<int>& nodes = mesh.boundary(plate.boundary).nodes;
  PlateReading r;
  r.boundary = plate.boundary;
  r.displacement = Eigen::VectorXd::Zero(dim);
  r.force = Eigen::VectorXd::Zero(dim);
  r.prescribed = plate.force;
  r.tied = plate.tied;
  r.held = plate.held;
  for (int node : nodes)
    for (int c = 0; c < dim; ++c) {
      r.displacement(c) += displacement(node * dim + c);
      r.force(c) += residual(node * dim + c);
    }
  if (!nodes.empty()) r.displacement /= static_cast<double>(nodes.size());
  for (int c : plate.held) r.displacement(c) = 0.0;
  return r;
}

}  // namespace frictopt::fem
