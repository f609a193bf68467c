// SPDX-License-Identifier: MIT
#include "case_geometry_section.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>

#include "case_mesh_section.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/mesh/graded_coordinates.hpp"
#include "text_input.hpp"

namespace frictopt::io::detail {
namespace {

// Bounds of mesh.grading: 1 is uniform; beyond 10 the top cells become so tall that the
// aspect ratio, not the contact zone, limits the accuracy.
constexpr double kMinGrading = 1.0;
constexpr double kMaxGrading = 10.0;

// Size limits (docs/case-format.md, "Size limits"), checked before anything is allocated:
// a case beyond them would exhaust the memory of a workstation or run for days, and the
// counts stay far inside int. The memory estimate of the message is calibrated on the
// 100,860-unknown punch (peak resident memory of `frictopt solve`, docs/case-format.md) and
// grows like the sparse Cholesky factor of a 3D grid, n^(4/3); 2D grows like n log n, for
// which n^(4/3) is an upper bound.
constexpr std::int64_t kMaxUnknowns = 2'000'000;
constexpr double kCalibrationUnknowns = 100'860.0;
constexpr double kCalibrationBytes = 1.85e9;  // 1,848,728 kB peak (GNU time), cases3d/punch-large

// Physical bounds (docs/case-format.md, "Physical bounds"): beyond them the numbers are
// outside linear elasticity or outside double precision, and the solvers would fail with
// messages that do not name the field.
constexpr double kMinLength = 1e-6;      // m
constexpr double kMaxLength = 1e6;       // m

double estimated_bytes(double unknowns) {
  return kCalibrationBytes * std::pow(unknowns / kCalibrationUnknowns, 4.0 / 3.0);
}

Geometry read_geometry(const TableReader& r) {
  Geometry g;
  g.dim = r.required_int("dim", "2 or 3");
  if (g.dim != 2 && g.dim != 3) r.fail_value("dim", "2 or 3");
  const auto length = [&](std::string_view key, std::string_view what) {
    const double x = r.required_number(key, what);
    if (!(x >= kMinLength && x <= kMaxLength))
      r.fail_value(key, fmt::format("{} <= {} <= {} m", kMinLength, key, kMaxLength));
    return x;
  };
  g.a = length("a", "a number > 0 (the length of the body in x1, m)");
  if (g.dim == 3) {
    g.b = length("b", "a number > 0 (the length of the body in x2, m) in 3D");
  } else if (r.has("b")) {
    r.fail("b", fmt::format("{} = {} is only allowed in 3D, but geometry.dim = 2; remove it or "
                            "set dim = 3",
                            r.field("b"), describe(*r.node("b"))));
  }
  g.height = length("height", "a number > 0 (the height C4 of the top, m)");
  return g;
}

// In-plane grading (docs/case-format.md, "[mesh]"): growth in (1, 2] switches it on, refine_box
// ([x1min, x1max] in 2D, [x1min, x1max, x2min, x2max] in 3D, metres) says where the columns
// are finest. Whether the cells suffice is checked here with the mesh's own construction of
// the column lines, so the message points at the case file's line.
void read_in_plane_grading(const TableReader& r, const Geometry& g, mesh::GridResolution& m) {
  if (auto growth = r.optional_number("growth")) {
    if (!(*growth >= 1.0 && *growth <= 2.0))
      r.fail_value("growth", "1 <= growth <= 2 (ratio of neighbouring in-plane cell sizes; 1 = uniform columns)");
    m.growth = *growth;
  }
  const std::array<double, 2> extent{g.a, g.b};
  if (r.has("refine_box")) {
    const std::string what =
        g.dim == 2 ? "a list of 2 numbers [x1min, x1max] in metres within [0, geometry.a]"
                   : "a list of 4 numbers [x1min, x1max, x2min, x2max] in metres within [0, geometry.a] x [0, geometry.b]";
    const std::vector<double> box = r.number_list("refine_box", what);
    if (static_cast<int>(box.size()) != 2 * (g.dim - 1)) r.fail_value("refine_box", what);
    if (m.growth == 1.0)
      r.fail("refine_box", fmt::format("{} is given but mesh.growth = 1 (uniform columns); expected also growth in "
                                       "(1, 2], e.g. growth = 1.2",
                                       r.field("refine_box")));
    std::array<double, 4> stored{0.0, 0.0, 0.0, 0.0};
    for (std::size_t i = 0; i < box.size(); ++i) {
      const double length = extent[i / 2];
      if (!(box[i] >= 0 && box[i] <= length))
        r.fail_entry("refine_box", i, fmt::format("a coordinate in [0, {}] m (geometry.{})", length, i < 2 ? "a" : "b"));
      if (i % 2 == 1 && !(box[i - 1] < box[i]))
        r.fail_entry("refine_box", i, fmt::format("a maximum > the minimum {} m", box[i - 1]));
      stored[i] = box[i];
    }
    m.refine_box = stored;
  }
  if (m.growth == 1.0) return;
  for (int c = 0; c < g.dim - 1; ++c) {
    const std::size_t i = static_cast<std::size_t>(c);
    const double length = extent[i];
    const double lo = m.refine_box ? (*m.refine_box)[2 * i] : length * (1 - mesh::kDefaultRefineFraction) / 2;
    const double hi = m.refine_box ? (*m.refine_box)[2 * i + 1] : length * (1 + mesh::kDefaultRefineFraction) / 2;
    try {
      (void)mesh::graded_coordinates(length, m.cells[i], lo, hi, m.growth, fmt::format("mesh.cells[{}]", c));
    } catch (const InvalidInput& e) {
      r.fail("cells", e.what());
    }
  }
}

mesh::GridResolution read_grid(const TableReader& r, const Geometry& geometry) {
  const int dim = geometry.dim;
  mesh::GridResolution m;
  const std::string layout = dim == 2 ? "[n1, n_vertical]" : "[n1, n2, n_vertical]";
  const std::string what =
      fmt::format("a list of {} integers >= 1 {} in {}", dim, layout, dim_name(dim));
  const std::vector<int> cells = r.int_list("cells", what);
  if (static_cast<int>(cells.size()) != dim) r.fail_value("cells", what);
  for (std::size_t i = 0; i < cells.size(); ++i)
    if (cells[i] < 1) r.fail_entry("cells", i, "an integer >= 1");
  // Counted in double: exact far beyond the limit and free of overflow (three factors <= 2^31).
  double nodes = 1.0;
  for (int c : cells) nodes *= static_cast<double>(c) + 1.0;
  const double unknowns = nodes * dim;
  if (unknowns > static_cast<double>(kMaxUnknowns))
    r.fail_value("cells", fmt::format("at most {} unknowns ({} per node): this grid has {:.4g} nodes and {:.4g} "
                                      "unknowns and would need about {:.3g} GB of memory (docs/case-format.md, "
                                      "\"Size limits\")",
                                      kMaxUnknowns, dim, nodes, unknowns, estimated_bytes(unknowns) / 1e9));
  // GridResolution keeps (n1, n2, n_vertical); n2 is unused (0) in 2D.
  m.cells = dim == 2 ? std::array<int, 3>{cells[0], 0, cells[1]} : std::array<int, 3>{cells[0], cells[1], cells[2]};
  if (auto grading = r.optional_number("grading")) {
    if (!(*grading >= kMinGrading && *grading <= kMaxGrading))
      r.fail_value("grading",
                   fmt::format("{} <= grading <= {} (1 = uniform)", kMinGrading, kMaxGrading));
    m.grading = *grading;
  }
  read_in_plane_grading(r, geometry, m);
  detail::read_vertical_grading(r, geometry.height, r.has("grading"), m);
  m.element_family = detail::read_element_family(r, dim);
  return m;
}

}  // namespace

Geometry read_geometry_section(const TableReader& top, std::string_view origin) {
  return read_geometry(required_table(top, "geometry", origin, {"dim", "a", "b", "height"}));
}

int read_imported_geometry_section(const TableReader& top, std::string_view origin) {
  const TableReader g = required_table(top, "geometry", origin, {"dim"});
  const int dim = g.required_int("dim", "2 or 3");
  if (dim != 2 && dim != 3) g.fail_value("dim", "2 or 3");
  return dim;
}

mesh::GridResolution read_grid_section(const TableReader& top, std::string_view origin, const Geometry& geometry) {
  return read_grid(required_table(top, "mesh", origin,
                                  {"cells", "grading", "growth", "refine_box", "vertical_grading", "fine_depth",
                                   "vertical_growth", "element"}),
                   geometry);
}

}  // namespace frictopt::io::detail
