// SPDX-License-Identifier: MIT
#include "frictopt/study/build_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>

#include <Eigen/Geometry>
#include <Eigen/QR>

#include "frictopt/core/error.hpp"
#include "frictopt/fem/boundary_conditions.hpp"
#include "frictopt/mesh/design_extension.hpp"
#include "frictopt/mesh/structured_mesh.hpp"

namespace frictopt::study {

mesh::Mesh build_mesh(const BodyDefinition& definition) {
  if (!definition.imported_mesh)
    return mesh::StructuredMesh(definition.shape, definition.height, definition.resolution).take_mesh();
  const ImportedMeshDefinition& imported = *definition.imported_mesh;
  if (!imported.reference) throw InvalidInput("imported mesh: no mesh was read");
  const mesh::Mesh& reference = *imported.reference;
  const std::string& patch = imported.motion.patch;
  // Γ_d ⊂ Γ_c (spec 07 §5): the gap of a contact node moves with the patch only.
  if (definition.contact) {
    const std::vector<int>& surface = reference.boundary(definition.contact_surface).nodes;
    const std::vector<int>& patch_nodes = reference.boundary(patch).nodes;
    if (!std::includes(surface.begin(), surface.end(), patch_nodes.begin(), patch_nodes.end()))
      throw InvalidInput(fmt::format("{}: the design patch '{}' is not part of the contact surface '{}'; expected a "
                                     "patch whose nodes all lie on the contact surface",
                                     imported.file.string(), patch, definition.contact_surface));
  }
  // The extension holds the Dirichlet parts and the contact surface off the patch (their nodes
  // do not move; patch nodes on them move with the patch): the body's clamps stay where the
  // case puts them, and a contact node off the patch keeps its gap.
  mesh::DesignMotion motion = imported.motion;
  for (const fem::FaceDirichlet& d : definition.dirichlet) motion.fixed.push_back(d.boundary);
  if (definition.contact && definition.contact_surface != patch) motion.fixed.push_back(definition.contact_surface);
  mesh::Mesh mesh = mesh::with_design_motion(reference, definition.shape, motion);
  check_rigid_modes_removed(mesh, definition.dirichlet, imported.file.string());
  return mesh;
}

void check_rigid_modes_removed(const mesh::Mesh& mesh, const std::vector<fem::FaceDirichlet>& dirichlet,
                               const std::string& file) {
  // The rigid motions r(x) = t + ω × x (3D: 6, 2D: 3) restricted to the prescribed DOFs: the
  // stiffness matrix of a connected body is nonsingular iff no rigid motion vanishes on all of
  // them, i.e. iff this restriction has full column rank.
  const int dim = mesh.dim();
  const int modes = dim == 3 ? 6 : 3;
  const fem::PrescribedDofs prescribed = fem::expand_dirichlet(mesh, dirichlet);
  const Eigen::MatrixXd& X = mesh.reference_positions();
  const Eigen::RowVectorXd centre = X.colwise().mean();
  const double size = (X.colwise().maxCoeff() - X.colwise().minCoeff()).maxCoeff();
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(prescribed.dofs.size()), modes);
  for (std::size_t k = 0; k < prescribed.dofs.size(); ++k) {
    const int node = prescribed.dofs[k] / dim, c = prescribed.dofs[k] % dim;
    const Eigen::VectorXd x = (X.row(node) - centre).transpose() / size;  // scaled: rank is unit-free
    const auto row = static_cast<Eigen::Index>(k);
    R(row, c) = 1.0;  // translation along c
    if (dim == 2) {
      R(row, 2) = c == 0 ? -x(1) : x(0);  // rotation about x3
    } else {
      // ω_j e_j × x, component c: (e_j × x)_c for j = 0, 1, 2.
      const Eigen::Vector3d y = x;
      for (int j = 0; j < 3; ++j) R(row, 3 + j) = Eigen::Vector3d::Unit(j).cross(y)(c);
    }
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(R);
  qr.setThreshold(1e-10);
  const Eigen::Index rank = R.rows() == 0 ? 0 : qr.rank();
  if (rank < modes) {
    std::string names;
    for (const fem::FaceDirichlet& d : dirichlet) names += (names.empty() ? "'" : ", '") + d.boundary + "'";
    throw InvalidInput(fmt::format("{}: the Dirichlet parts ({}) leave {} of the body's {} rigid-body motions free "
                                   "(the stiffness matrix would be singular); expected conditions that fix every "
                                   "translation and rotation, e.g. all components on one group",
                                   file, names, modes - rank, modes));
  }
}

}  // namespace frictopt::study
