// SPDX-License-Identifier: MIT
#include "frictopt/fem/node_selection.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <limits>

#include "element_kernels.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/mesh/elements.hpp"

namespace frictopt::fem {
namespace {

std::string vector_text(const Eigen::VectorXd& v) {
  std::string s = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) s += fmt::format("{}{:.6g}", i ? ", " : "", v(i));
  return s + "]";
}

}  // namespace

std::vector<int> select_nodes(const mesh::Mesh& mesh, const NodeSelector& s,
                              const std::string& field) {
  const int dim = mesh.dim();
  const int selectors = int(s.point.has_value()) +
                        int(s.box_min.has_value() || s.box_max.has_value()) +
                        int(s.boundary.has_value());
  if (selectors != 1)
    throw InvalidInput(
        fmt::format("{}: {} node selectors given; expected exactly one of `at` (a point), "
                    "`box_min`+`box_max` (a box) or `boundary` (a named set)",
                    field, selectors));
  const Eigen::MatrixXd& X = mesh.reference_positions();
  std::vector<int> nodes;
  if (s.point) {
    if (s.point->size() != dim)
      throw InvalidInput(
          fmt::format("{}.at has {} entries; expected {}", field, s.point->size(), dim));
    if (!(s.tolerance >= 0.0))
      throw InvalidInput(fmt::format("{}.tolerance = {}; expected >= 0", field, s.tolerance));
    int best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int n = 0; n < mesh.num_nodes(); ++n) {
      const double d = (X.row(n).transpose() - *s.point).norm();
      if (d < best_distance) best_distance = d, best = n;  // first nearest: deterministic
    }
    if (!(best_distance <= s.tolerance))
      throw InvalidInput(
          fmt::format("{}.at = {}: the nearest node {} at {} is {:.6g} m away; expected a node "
                      "within tolerance = {:.6g} m (raise the tolerance or move the point)",
                      field, vector_text(*s.point), best, vector_text(X.row(best).transpose()),
                      best_distance, s.tolerance));
    nodes.push_back(best);
  } else if (s.box_min || s.box_max) {
    if (!s.box_min || !s.box_max || s.box_min->size() != dim || s.box_max->size() != dim)
      throw InvalidInput(
          fmt::format("{}: a box needs box_min and box_max with {} entries each", field, dim));
    for (int n = 0; n < mesh.num_nodes(); ++n) {
      const Eigen::VectorXd x = X.row(n).transpose();
      if ((x.array() >= s.box_min->array()).all() && (x.array() <= s.box_max->array()).all())
        nodes.push_back(n);
    }
    if (nodes.empty())
      throw InvalidInput(fmt::format(
          "{}: the box {} .. {} holds no node of the reference mesh; expected at least one", field,
          vector_text(*s.box_min), vector_text(*s.box_max)));
  } else {
    if (!mesh.has_boundary(*s.boundary))
      throw InvalidInput(
          fmt::format("{}.boundary = \"{}\": the mesh has no such set; expected one of {}", field,
                      *s.boundary, fmt::join(mesh.boundary_names(), ", ")));
    nodes = mesh.boundary(*s.boundary).nodes;
  }
  return nodes;
}

void add_nodal_constraints(const mesh::Mesh& mesh, const std::vector<NodalConstraint>& constraints,
                           PrescribedDofs& prescribed) {
  const int dim = mesh.dim();
  std::vector<char> fixed(static_cast<std::size_t>(mesh.num_dofs()), 0);
  for (int d : prescribed.dofs) fixed[static_cast<std::size_t>(d)] = 1;
  for (std::size_t k = 0; k < constraints.size(); ++k) {
    const std::string field = fmt::format("constraint[{}]", k);
    const NodalConstraint& c = constraints[k];
    if (c.displacement.size() != 0 && (c.displacement.size() != dim || !c.displacement.allFinite()))
      throw InvalidInput(fmt::format("{}.displacement = {}; expected {} finite entries", field,
                                     vector_text(c.displacement), dim));
    std::vector<int> components = c.components;
    if (components.empty())
      for (int comp = 0; comp < dim; ++comp) components.push_back(comp);
    for (int comp : components)
      if (comp < 0 || comp >= dim)
        throw InvalidInput(fmt::format("{}.components: {} is not a component index; expected 0..{}",
                                       field, comp, dim - 1));
    for (int n : select_nodes(mesh, c.where, field))
      for (int comp : components) {
        const int dof = n * dim + comp;
        if (fixed[static_cast<std::size_t>(dof)])
          throw InvalidInput(fmt::format(
              "{} fixes component {} of node {}, which a [[dirichlet]] table or an earlier "
              "[[constraint]] already fixes; expected each DOF fixed once",
              field, comp, n));
        fixed[static_cast<std::size_t>(dof)] = 1;
        prescribed.dofs.push_back(dof);
        prescribed.values.push_back(c.displacement.size() ? c.displacement(comp) : 0.0);
      }
  }
}

Eigen::VectorXd nodal_force_load(const mesh::Mesh& mesh, const DofMap& dofs,
                                 const std::vector<NodalForce>& forces) {
  const int dim = mesh.dim();
  Eigen::VectorXd l = Eigen::VectorXd::Zero(mesh.num_dofs());
  for (std::size_t k = 0; k < forces.size(); ++k) {
    const std::string field = fmt::format("force[{}]", k);
    const NodalForce& f = forces[k];
    if (f.force.size() != dim || !f.force.allFinite())
      throw InvalidInput(fmt::format("{}.force = {}; expected {} finite entries", field,
                                     vector_text(f.force), dim));
    const std::vector<int> nodes = select_nodes(mesh, f.where, field);
    for (int n : nodes)
      for (int c = 0; c < dim; ++c) {
        if (f.force(c) == 0.0) continue;
        if (!dofs.is_free(n * dim + c))
          throw InvalidInput(
              fmt::format("{}.force[{}] = {:.6g} acts on node {} in component {}, which a "
                          "[[dirichlet]] table prescribes; expected 0 there (a force on a fixed "
                          "component is taken by the support and does nothing)",
                          field, c, f.force(c), n, c));
        l(n * dim + c) += f.force(c) / static_cast<double>(nodes.size());
      }
  }
  return l;
}

Eigen::VectorXd face_traction_load(const mesh::Mesh& mesh,
                                   const Eigen::Ref<const Eigen::MatrixXd>& X,
                                   const FaceTraction& traction) {
  if (traction.traction.size() != mesh.dim())
    throw InvalidInput(fmt::format("traction on face \"{}\" has {} entries; expected {}",
                                   traction.boundary, traction.traction.size(), mesh.dim()));
  const mesh::Connectivity& facets =
      mesh.boundary(traction.boundary).facets;  // throws for unknown names
  // The same kernel and loop as LinearElasticity::traction_load, for one face only.
  return mesh::with_element(mesh.element_kind(), [&](auto element) {
    using Element = decltype(element);
    constexpr int Dim = Element::kDim;
    using Facet = detail::FacetKernel<Element>;
    Eigen::VectorXd l = Eigen::VectorXd::Zero(mesh.num_dofs());
    const Eigen::Matrix<double, Dim, 1> t = traction.traction;
    for (Eigen::Index f = 0; f < facets.rows(); ++f) {
      typename Facet::Coordinates Xf;
      for (int a = 0; a < Facet::kNodes; ++a) Xf.row(a) = X.row(facets(f, a));
      const typename Facet::Coordinates forces = Facet::load(Xf, t);
      for (int a = 0; a < Facet::kNodes; ++a)
        l.segment(facets(f, a) * Dim, Dim) += forces.row(a).transpose();
    }
    return l;
  });
}

}  // namespace frictopt::fem
