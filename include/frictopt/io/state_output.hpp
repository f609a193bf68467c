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
/// "stress" and "von_mises" at element centres.
[[nodiscard]] VtuGrid make_state_grid(const study::ElasticBody& body, const study::BodyState& state);

/// make_state_grid + write_vtu.
void write_state_vtu(const std::filesystem::path& path, const study::ElasticBody& body, const study::BodyState& state);

}  // namespace frictopt::io
