// SPDX-License-Identifier: MIT
// Writes the state of a body (deformed shape, displacement, stresses, boundary tags) as VTK.
#pragma once

#include <filesystem>

#include "frictopt/io/vtu_writer.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::io {

/// Bit flags of the point array "boundary_tag": which boundary parts a node lies on.
enum BoundaryTag : int { kContactTag = 1, kDirichletTag = 2, kTractionTag = 4 };

/// The body at `state` as a VtuGrid: points at X(α) (undeformed configuration of the design;
/// warp by "displacement" in ParaView), Q1 cells, point data "displacement", "stress"
/// (symmetric tensor, Pa), "von_mises" (Pa), "boundary_tag" (BoundaryTag bits), cell data
/// "stress" and "von_mises" at element centres; with contact also the arrays of add_contact_fields.
[[nodiscard]] VtuGrid make_state_grid(const study::ElasticBody& body,
                                      const study::BodyState& state);

/// Projected area of Γ_c attributed to each contact node (p entries) [m², 2D: m per metre].
[[nodiscard]] Eigen::VectorXd contact_tributary_areas(const study::ElasticBody& body);

/// Adds the contact point arrays (NaN off Γ_c): "contact_pressure" λ/area [Pa],
/// "contact_traction" τ/area [Pa] (tangential, on the body), "slip" u_t [m], "contact_gap"
/// u_ν + g [m], "contact_status" (−1 not a contact node, 0 separated, 1 stick, 2 slip).
void add_contact_fields(VtuGrid& grid, const study::ElasticBody& body, const study::ContactResult& result);

/// 2D: a CSV along Γ_c with one row per contact node: x1, gap g, λ, pressure, τ, traction,
/// u_t, u_ν + g, status.
void write_contact_csv(const std::filesystem::path& path, const study::ElasticBody& body,
                       const study::ContactResult& result);

/// make_state_grid + write_vtu.
void write_state_vtu(const std::filesystem::path& path, const study::ElasticBody& body,
                     const study::BodyState& state);

}  // namespace frictopt::io
