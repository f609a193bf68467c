// SPDX-License-Identifier: MIT
// The mesh of a body definition, from whichever producer the definition names.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "frictopt/fem/boundary_conditions.hpp"
#include "frictopt/mesh/mesh.hpp"
#include "frictopt/study/body_definition.hpp"

namespace frictopt::study {

/// The structured grid of definition.shape, height and resolution (mesh::StructuredMesh), or,
/// with definition.imported_mesh, the imported mesh with the design motion of its patch
/// (mesh::with_design_motion: patch nodes along the foundation normal by the Bézier surface, the
/// rest by the once-per-mesh extension, which holds the Dirichlet parts and, with contact, the
/// contact surface off the patch). Throws InvalidInput as those producers do, and for a
/// design patch that is not part of the contact surface, and for an imported body without
/// contact whose Dirichlet parts leave a rigid-body motion free (check_rigid_modes_removed; with
/// contact such a body floats, held by contact and friction as on the box).
mesh::Mesh build_mesh(const BodyDefinition& definition);

/// The size limits every body's mesh meets before anything is assembled (docs/case-format.md,
/// "Size limits"), whichever producer made it: at most kMaxUnknowns unknowns, and a peak memory
/// estimate (estimated_peak_bytes) within the memory limit (set_memory_limit; by default the
/// memory available, mesh::available_memory_bytes). build_mesh calls it; throws InvalidInput
/// naming `source`, the counts, the estimate and the limit.
/// `contact_nodes` (the nodes of the contact surface, 0 without contact) adds the contact
/// algebra's memory (estimated_contact_bytes) to the estimate and is named in the message.
void check_mesh_size(const mesh::Mesh& mesh, const std::string& source, std::int64_t contact_nodes = 0);

/// The memory [bytes] of the direct engine's contact algebra for m = dim × contact nodes contact
/// unknowns (docs/scaling.md, "Contact nodes"): the dense Delassus matrix, 8·m² for m up to
/// 12,000 (above: its working-set block, counted as 12,000), and from m = 3,000 on the
/// single-precision LU of the semismooth Newton Jacobian, 4·m² (docs/contact.md, "Semismooth
/// Newton").
double estimated_contact_bytes(std::int64_t contact_unknowns);

/// The dense contact algebra's flops for m contact unknowns: forming M from the Schur factor
/// (dpotri, 2m³/3) and, from m = 3,000 on, a few single-precision LU factorizations of Newton
/// Jacobians (2m³/3 each, counted three times: the measured 2–4 per state). What a state costs
/// beyond the sparse factorization when the contact surface is large.
double estimated_contact_flops(std::int64_t contact_unknowns);

/// A note for the console when the contact algebra of `contact_nodes` nodes in dimension `dim`
/// is large (above 1 GB or 5·10¹⁰ flops, about 5 s: from about 3,000 contact unknowns on): its
/// memory and flops and what to do; empty otherwise.
std::string contact_cost_note(int dim, std::int64_t contact_nodes);

/// The largest number of unknowns (nodes × dim) of a body.
inline constexpr std::int64_t kMaxUnknowns = 2'000'000;

/// The peak resident memory [bytes] of a state solve with `unknowns` unknowns (direct engine):
/// 2.07 GB at 100,900 unknowns growing like n^(4/3), the sparse Cholesky factor of a 3D grid
/// (measured peaks: 0.38 GB at 22.5k, 2.07 GB at 100.9k, 4.86 GB at 195k unknowns; the formula
/// gives 0.28, 2.07 and 4.97 GB). An upper bound for 2D bodies (n log n).
double estimated_peak_bytes(std::int64_t unknowns);

/// The most unknowns (at most kMaxUnknowns, at least 1) whose estimated_peak_bytes fits the
/// memory limit of check_mesh_size (memory_limit(), else the memory available): what a Gmsh
/// child process that meshes a body's .geo is given memory for (mesh::GmshMeshOptions).
[[nodiscard]] std::int64_t max_unknowns_within_memory();

/// The memory limit of check_mesh_size [bytes], process-wide (the command line's --max-memory);
/// 0 (the default) means the memory available when the mesh is checked.
void set_memory_limit(std::uint64_t bytes);
std::uint64_t memory_limit();

/// Throws InvalidInput naming `file` and the Dirichlet groups when the prescribed DOFs of
/// `dirichlet` leave a rigid-body motion of `mesh` free (3D: 3 translations and 3 rotations;
/// 2D: 2 and 1), i.e. the stiffness matrix would be singular.
void check_rigid_modes_removed(const mesh::Mesh& mesh, const std::vector<fem::FaceDirichlet>& dirichlet,
                               const std::string& file);

}  // namespace frictopt::study
