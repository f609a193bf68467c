// SPDX-License-Identifier: MIT
#include "frictopt/fem/boundary_conditions.hpp"

#include <fmt/format.h>

#include <map>

#include "frictopt/core/error.hpp"

namespace frictopt::fem {

PrescribedDofs expand_dirichlet(const mesh::Mesh& mesh,
                                const std::vector<FaceDirichlet>& conditions) {
  const int dim = mesh.dim();
  std::map<int, double> values;
  for (std::size_t i = 0; i < conditions.size(); ++i) {
    const FaceDirichlet& c = conditions[i];
    if (c.displacement.size() != 0 && c.displacement.size() != dim)
      throw InvalidInput(fmt::format("dirichlet[{}].displacement has {} entries; expected {}", i,
                                     c.displacement.size(), dim));
    std::vector<int> components = c.components;
    if (components.empty())
      for (int k = 0; k < dim; ++k) components.push_back(k);
    for (int k : components)
      if (k < 0 || k >= dim)
        throw InvalidInput(fmt::format("dirichlet[{}].components contains {}; expected 0..{}", i, k, dim - 1));
    for (int node : mesh.boundary(c.boundary).nodes)
      for (int k : components) values[node * dim + k] = c.displacement.size() ? c.displacement(k) : 0.0;
  }
  PrescribedDofs out;
  for (const auto& [dof, value] : values) {
    out.dofs.push_back(dof);
    out.values.push_back(value);
  }
  return out;
}

DofMap::DofMap(int num_dofs, const PrescribedDofs& prescribed, const std::vector<std::vector<int>>& ties)
    : free_index_(num_dofs, 0), ties_(ties), prescribed_values_(Eigen::VectorXd::Zero(num_dofs)) {
  for (std::size_t i = 0; i < prescribed.dofs.size(); ++i) {
    const int dof = prescribed.dofs[i];
    if (dof < 0 || dof >= num_dofs)
      throw InvalidInput(fmt::format("prescribed dof {} out of range [0, {})", dof, num_dofs));
    free_index_[dof] = -1;
    prescribed_values_(dof) = prescribed.values[i];
  }
  // group[dof]: the tie group of a DOF or −1.
  std::vector<int> group(static_cast<std::size_t>(num_dofs), -1);
  for (std::size_t g = 0; g < ties_.size(); ++g) {
    if (ties_[g].empty()) throw InvalidInput(fmt::format("tie group {} has no DOF; expected at least one", g));
    for (int dof : ties_[g]) {
      if (dof < 0 || dof >= num_dofs)
        throw InvalidInput(fmt::format("tied dof {} out of range [0, {})", dof, num_dofs));
      if (free_index_[dof] < 0)
        throw InvalidInput(fmt::format("dof {} (tie group {}) is both prescribed and tied; expected one", dof, g));
      if (group[static_cast<std::size_t>(dof)] >= 0)
        throw InvalidInput(fmt::format("dof {} is in tie groups {} and {}; expected at most one", dof,
                                       group[static_cast<std::size_t>(dof)], g));
      group[static_cast<std::size_t>(dof)] = static_cast<int>(g);
    }
  }
  std::vector<int> group_index(ties_.size(), -1);
  for (int dof = 0; dof < num_dofs; ++dof) {
    if (free_index_[dof] < 0) continue;
    const int g = group[static_cast<std::size_t>(dof)];
    if (g >= 0 && group_index[static_cast<std::size_t>(g)] >= 0) {
      free_index_[dof] = group_index[static_cast<std::size_t>(g)];  // the group's unknown
      continue;
    }
    free_index_[dof] = static_cast<int>(free_dofs_.size());
    free_dofs_.push_back(dof);
    if (!ties_.empty()) tie_of_.push_back(g);
    if (g >= 0) group_index[static_cast<std::size_t>(g)] = free_index_[dof];
  }
}

Eigen::VectorXd DofMap::expand(const Eigen::Ref<const Eigen::VectorXd>& free_values) const {
  FRICTOPT_ASSERT(free_values.size() == num_free(), "free vector size");
  Eigen::VectorXd full = prescribed_values_;
  for (int dof = 0; dof < num_dofs(); ++dof)
    if (free_index_[dof] >= 0) full(dof) = free_values(free_index_[dof]);
  return full;
}

Eigen::VectorXd DofMap::expand_homogeneous(const Eigen::Ref<const Eigen::VectorXd>& free_values) const {
  FRICTOPT_ASSERT(free_values.size() == num_free(), "free vector size");
  Eigen::VectorXd full = Eigen::VectorXd::Zero(num_dofs());
  for (int dof = 0; dof < num_dofs(); ++dof)
    if (free_index_[dof] >= 0) full(dof) = free_values(free_index_[dof]);
  return full;
}

Eigen::VectorXd DofMap::restrict(const Eigen::Ref<const Eigen::VectorXd>& full) const {
  FRICTOPT_ASSERT(full.size() == num_dofs(), "full vector size");
  Eigen::VectorXd out(num_free());
  for (int i = 0; i < num_free(); ++i) out(i) = full(free_dofs_[i]);
  return out;
}

Eigen::VectorXd DofMap::restrict_forces(const Eigen::Ref<const Eigen::VectorXd>& full) const {
  FRICTOPT_ASSERT(full.size() == num_dofs(), "full vector size");
  if (ties_.empty()) return restrict(full);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(num_free());
  for (int dof = 0; dof < num_dofs(); ++dof)
    if (free_index_[dof] >= 0) out(free_index_[dof]) += full(dof);
  return out;
}

}  // namespace frictopt::fem
