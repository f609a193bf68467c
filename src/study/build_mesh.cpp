// SPDX-License-Identifier: MIT
#include "frictopt/study/build_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

#include <Eigen/Geometry>
#include <Eigen/QR>

#include "frictopt/core/error.hpp"
#include "frictopt/fem/boundary_conditions.hpp"
#include "frictopt/mesh/design_extension.hpp"
#include "frictopt/mesh/gmsh_mesh.hpp"
#include "frictopt/mesh/structured_mesh.hpp"

namespace frictopt::study {

namespace {

// Calibration of estimated_peak_bytes: peak resident memory of `frictopt solve` on the punch at
// 100,900 unknowns (docs/case-format.md, "Size limits").
constexpr double kCalibrationUnknowns = 100'900.0;
constexpr double kCalibrationBytes = 2.07e9;

std::atomic<std::uint64_t>& memory_limit_bytes() {
  static std::atomic<std::uint64_t> limit{0};
  return limit;
}

}  // namespace

double estimated_peak_bytes(std::int64_t unknowns) {
  return kCalibrationBytes * std::pow(static_cast<double>(unknowns) / kCalibrationUnknowns, 4.0 / 3.0);
}

void set_memory_limit(std::uint64_t bytes) { memory_limit_bytes().store(bytes); }
std::uint64_t memory_limit() { return memory_limit_bytes().load(); }

std::int64_t max_unknowns_within_memory() {
  const std::uint64_t set = memory_limit();
  const std::uint64_t limit = set > 0 ? set : mesh::available_memory_bytes();
  const auto fits = [&](std::int64_t n) { return estimated_peak_bytes(n) <= static_cast<double>(limit); };
  if (limit == 0 || fits(kMaxUnknowns)) return kMaxUnknowns;
  std::int64_t lo = 1, hi = kMaxUnknowns;  // estimated_peak_bytes increases: bisect on fits
  while (hi - lo > 1) {
    const std::int64_t mid = lo + (hi - lo) / 2;
    (fits(mid) ? lo : hi) = mid;
  }
  return lo;
}

namespace {
// The dense Delassus bound (ContactDefinition::dense_delassus_max_unknowns) and the size from
// which kAutomatic may hand over to the semismooth Newton method
// (CoulombSolver::Options::NewtonOptions::automatic_min_unknowns).
constexpr std::int64_t kDenseContactUnknowns = 12'000;
constexpr std::int64_t kNewtonContactUnknowns = 3'000;
}  // namespace

double estimated_contact_bytes(std::int64_t contact_unknowns) {
  const double m = static_cast<double>(std::min(contact_unknowns, kDenseContactUnknowns));
  return 8.0 * m * m + (contact_unknowns >= kNewtonContactUnknowns ? 4.0 * m * m : 0.0);
}

double estimated_contact_flops(std::int64_t contact_unknowns) {
  const double m = static_cast<double>(std::min(contact_unknowns, kDenseContactUnknowns));
  const double lu = 2.0 / 3.0 * m * m * m;
  return lu + (contact_unknowns >= kNewtonContactUnknowns ? 3.0 * lu : 0.0);
}

std::string contact_cost_note(int dim, std::int64_t contact_nodes) {
  const std::int64_t m = dim * contact_nodes;
  const double bytes = estimated_contact_bytes(m), flops = estimated_contact_flops(m);
  if (bytes < 1e9 && flops < 5e10) return {};
  return fmt::format("{} contact nodes ({} contact unknowns): the dense contact algebra needs about {:.3g} GB and "
                     "{:.2g} flops (about {:.0f} s at 10 Gflop/s) beyond the factorization (docs/scaling.md, "
                     "\"Contact nodes\"; a coarser contact surface reduces it quadratically in memory and cubically "
                     "in time)",
                     contact_nodes, m, bytes / 1e9, flops, flops / 1e10);
}

void check_mesh_size(const mesh::Mesh& mesh, const std::string& source, std::int64_t contact_nodes) {
  const std::int64_t unknowns = static_cast<std::int64_t>(mesh.num_nodes()) * mesh.dim();
  const double contact_bytes = estimated_contact_bytes(mesh.dim() * contact_nodes);
  const double estimate = estimated_peak_bytes(unknowns) + contact_bytes;
  const std::string contact =
      contact_nodes > 0 ? fmt::format(" and {} contact nodes ({:.3g} GB of it the dense contact algebra)",
                                      contact_nodes, contact_bytes / 1e9)
                        : std::string();
  if (unknowns > kMaxUnknowns)
    throw InvalidInput(fmt::format("{}: the body has {} nodes, {} unknowns; expected at most {} unknowns (about {:.3g} GB "
                                   "of memory; docs/case-format.md, \"Size limits\")",
                                   source, mesh.num_nodes(), unknowns, kMaxUnknowns, estimate / 1e9));
  const std::uint64_t set = memory_limit();
  const std::uint64_t limit = set > 0 ? set : mesh::available_memory_bytes();
  if (limit > 0 && estimate > static_cast<double>(limit))
    throw InvalidInput(fmt::format("{}: the body has {} unknowns{}, whose solve needs about {:.3g} GB of memory; expected "
                                   "at most {:.3g} GB ({}; docs/case-format.md, \"Size limits\": a coarser mesh, or "
                                   "--max-memory GB to allow more)",
                                   source, unknowns, contact, estimate / 1e9, static_cast<double>(limit) / 1e9,
                                   set > 0 ? "the --max-memory limit" : "the memory available on this machine"));
}

namespace {
// The nodes of the contact surface (an upper bound of the contact nodes: nodes with a prescribed
// component are not contact nodes); 0 without contact or when the set is missing (refused later
// with its own message).
std::int64_t contact_node_count(const mesh::Mesh& mesh, const BodyDefinition& definition) {
  if (!definition.contact || !mesh.has_boundary(definition.contact_surface)) return 0;
  return static_cast<std::int64_t>(mesh.boundary(definition.contact_surface).nodes.size());
}
}  // namespace

mesh::Mesh build_mesh(const BodyDefinition& definition) {
  if (!definition.imported_mesh) {
    mesh::Mesh grid = mesh::StructuredMesh(definition.shape, definition.height, definition.resolution).take_mesh();
    check_mesh_size(grid, "mesh.cells", contact_node_count(grid, definition));
    return grid;
  }
  const ImportedMeshDefinition& imported = *definition.imported_mesh;
  if (!imported.reference) throw InvalidInput("imported mesh: no mesh was read");
  const mesh::Mesh& reference = *imported.reference;
  check_mesh_size(reference, imported.file.string(), contact_node_count(reference, definition));
  const std::string& patch = imported.motion.patch;
  // Γ_d ⊂ Γ_c (docs/meshes.md, "The design on a patch"): the gap of a contact node moves with the
  // patch only.
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
  // A loading plate's part stays where the case puts it too (docs/theory/loading-plate.md).
  for (const fem::LoadingPlate& p : definition.plates)
    if (reference.has_boundary(p.boundary)) motion.fixed.push_back(p.boundary);
  if (definition.contact && definition.contact_surface != patch) motion.fixed.push_back(definition.contact_surface);
  mesh::Mesh mesh = mesh::with_design_motion(reference, definition.shape, motion);
  // With contact, rigid motions the Dirichlet parts leave free are held by contact and friction
  // (a floating body, ElasticBody; docs/experiments.md §5): a body loaded by a force with
  // no clamp, or with only some components held, is as admissible as on the box. Without contact
  // nothing holds them.
  if (!definition.contact) check_rigid_modes_removed(mesh, definition.dirichlet, imported.file.string());
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
