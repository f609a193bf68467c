// SPDX-License-Identifier: MIT
// The case-file parser: one read_<table> function per TOML table, each on a strict
// TableReader that rejects unknown keys before it reads anything (so a misspelt key is
// reported as such, not as the missing key it was meant to be). Adding a table = adding a
// key to kRootKeys and one function. Schema: docs/case-format.md.
#include "frictopt/io/case_file.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <limits>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>

#include "frictopt/core/enum_table.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/core/validation.hpp"
#include "frictopt/mesh/face.hpp"
#include "frictopt/mesh/graded_coordinates.hpp"
#include "frictopt/study/shape_optimization.hpp"
#include "case_solver_section.hpp"
#include "case_load_case_section.hpp"
#include "case_plate_section.hpp"
#include "case_program_section.hpp"
#include "case_foundation_section.hpp"
#include "case_identification_section.hpp"
#include "case_mesh_section.hpp"
#include "text_input.hpp"
#include "toml_reader.hpp"

namespace frictopt::io {
namespace {

using detail::describe;
using detail::TableReader;

// Default polygon size for the 3D isotropic and elliptic laws: the thesis' 3D runs use
// n-gons, and n = 16 keeps the polygon within 2% of the disc (1 − cos(π/16) ≈ 0.019).
constexpr int kDefaultPolygonSides = 16;

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
constexpr int kMaxControlPointsPerDirection = 64;  // Bernstein degree 63
constexpr std::int64_t kMaxDesignVariables = 1024;  // the bundle QP is dense in d
constexpr int kMaxPolygonSides = 256;               // 1 − cos(π/256) < 1e-4 of the disc

// Physical bounds (docs/case-format.md, "Physical bounds"): beyond them the numbers are
// outside linear elasticity or outside double precision, and the solvers would fail with
// messages that do not name the field.
constexpr double kMinYoung = 1.0;        // Pa: softer than any solid (gels are ~1e2 Pa)
constexpr double kMaxYoung = 1e13;       // Pa: stiffer than diamond (1.2e12 Pa)
constexpr double kMaxPoisson = 0.49;     // Q1 elements lock beyond; λ/μ = 49 here
constexpr double kMinLength = 1e-6;      // m
constexpr double kMaxLength = 1e6;       // m
constexpr double kMaxFriction = 10.0;    // no dry-friction pair comes near

double estimated_bytes(double unknowns) {
  return kCalibrationBytes * std::pow(unknowns / kCalibrationUnknowns, 4.0 / 3.0);
}

std::string_view dim_name(int dim) { return dim == 2 ? "2D" : "3D"; }

std::string faces_for(int dim) {
  return dim == 2 ? "left, right, top" : "left, right, front, back, top";
}

// The shape of the friction set as a case file spells it ([contact.friction].kind). It is the
// syntax of the table, not a second friction-law type: read_friction turns it into a
// contact::FrictionLaw at once, and read_identification_section needs it for the parameter names
// (2D "isotropic" is the interval law, "none" names no coefficient).
enum class FrictionKind { kNone, kIsotropic, kPolygon, kEllipse, kEllipseExact, kDiscExact };
constexpr auto kFrictionKindNames = frictopt::detail::make_enum_table<FrictionKind>(
    std::pair{FrictionKind::kNone, "none"}, std::pair{FrictionKind::kIsotropic, "isotropic"},
    std::pair{FrictionKind::kPolygon, "polygon"}, std::pair{FrictionKind::kEllipse, "ellipse"},
    std::pair{FrictionKind::kEllipseExact, "ellipse_exact"}, std::pair{FrictionKind::kDiscExact, "disc_exact"});

// [geometry]: the box (0,a)×(0,b)×(G_α, height) (docs/theory/problem.md §2); its numbers go into
// the Bézier shape (a, b) and the body (height).
struct Geometry {
  int dim = 2;
  double a = 0.0, b = 0.0, height = 0.0;
};

// ---------------------------------------------------------------------------------------
// Shared readers

// A face of the structured box by its boundary-set name ("left", ..., "top"; the bottom is Γ_c).
std::string read_face(const TableReader& r, int dim) {
  const std::string text = r.required_string("face", fmt::format("one of {}", faces_for(dim)));
  if (text == "bottom")
    r.fail_value("face", fmt::format("one of {}; the bottom is the contact surface and "
                                     "carries neither loads nor Dirichlet conditions",
                                     faces_for(dim)));
  std::optional<mesh::Face> face;
  try {
    face = mesh::parse_face(text);
  } catch (const InvalidInput&) {
  }
  if (!face || (dim == 2 && (*face == mesh::Face::kFront || *face == mesh::Face::kBack)))
    r.fail_value("face", fmt::format("one of {} in {}", faces_for(dim), dim_name(dim)));
  return std::string(mesh::to_string(*face));
}

// A list of exactly `dim` numbers at `key`; `meaning` says what it is ("traction [N/m²]").
Eigen::VectorXd read_dim_vector(const TableReader& r, std::string_view key, int dim,
                                std::string_view meaning) {
  const std::string what =
      fmt::format("a list of {} numbers ({}) in {}", dim, meaning, dim_name(dim));
  const std::vector<double> v = r.number_list(key, what);
  if (static_cast<int>(v.size()) != dim) r.fail_value(key, what);
  return Eigen::Map<const Eigen::VectorXd>(v.data(), dim);
}

template <class Enum, std::size_t N>
std::optional<Enum> read_enum(const TableReader& r, std::string_view key,
                              const frictopt::detail::EnumTable<Enum, N>& table) {
  const std::optional<std::string> text = r.optional_string(key);
  if (!text) return std::nullopt;
  const std::optional<Enum> value = table.find(*text);
  if (!value) r.fail_value(key, fmt::format("one of {}", table.spellings()));
  return value;
}

// ---------------------------------------------------------------------------------------
// One function per table

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

mesh::GridResolution read_mesh(const TableReader& r, const Geometry& geometry) {
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
  return m;
}

fem::IsotropicMaterial read_material(const TableReader& r, int dim) {
  fem::IsotropicMaterial m;
  m.young = r.required_number("young", "a number > 0 (Young's modulus, Pa)");
  if (!(m.young > 0)) r.fail_value("young", "young > 0");
  if (!(m.young >= kMinYoung && m.young <= kMaxYoung))
    r.fail_value("young", fmt::format("{:g} Pa <= young <= {:g} Pa (Young's modulus in Pa; docs/case-format.md, "
                                      "\"Physical bounds\")",
                                      kMinYoung, kMaxYoung));
  m.poisson = r.required_number("poisson", "a number in [0, 0.5) (Poisson's ratio)");
  if (!(m.poisson >= 0 && m.poisson < 0.5)) r.fail_value("poisson", "0 <= poisson < 0.5");
  if (!(m.poisson <= kMaxPoisson))
    r.fail_value("poisson", fmt::format("0 <= poisson <= {} (Q1 elements lock for a nearly incompressible "
                                        "material and the solvers lose their accuracy; docs/case-format.md)",
                                        kMaxPoisson));
  if (dim == 3 && r.has("model"))
    r.fail("model", fmt::format("{} = {} is only allowed in 2D, but geometry.dim = 3",
                                r.field("model"), describe(*r.node("model"))));
  if (auto model = read_enum(r, "model", fem::kPlaneModelNames)) m.plane_model = *model;
  return m;
}

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

// [design] into the body: the Bézier shape over the geometry's base, Υ and α⁰.
void read_design(const TableReader& r, const Geometry& g, study::BodyDefinition& body) {
  shape::AdmissibleSetParameters& d = body.admissible;
  d.height = g.height;
  const int dim = g.dim;
  const std::string what =
      dim == 2 ? "a list [m1] of 1 integer >= 2 in 2D" : "a list [m1, m2] of 2 integers >= 2 in 3D";
  const std::vector<int> control_points = r.int_list("control_points", what);
  if (static_cast<int>(control_points.size()) != dim - 1) r.fail_value("control_points", what);
  std::int64_t num_controls = 1;
  for (std::size_t i = 0; i < control_points.size(); ++i) {
    if (control_points[i] < 2 || control_points[i] > kMaxControlPointsPerDirection)
      r.fail_entry("control_points", i,
                   fmt::format("an integer in [2, {}] (Bézier degree <= {})", kMaxControlPointsPerDirection,
                               kMaxControlPointsPerDirection - 1));
    num_controls *= control_points[i];
  }
  if (num_controls > kMaxDesignVariables)
    r.fail_value("control_points", fmt::format("at most {} design variables in all; this net has {}",
                                               kMaxDesignVariables, num_controls));
  body.shape = dim == 2 ? shape::BezierShape::curve(g.a, control_points[0])
                        : shape::BezierShape::surface(g.a, g.b, control_points[0], control_points[1]);

  d.upper_bound = r.required_number("upper_bound", "a number > 0 (the bound C0 on α, m)");
  if (!(d.upper_bound > 0 && d.upper_bound < g.height))
    r.fail_value("upper_bound", fmt::format("0 < upper_bound < geometry.height = {} (a control "
                                            "point at the top would collapse the body)",
                                            g.height));

  const int m = body.shape.num_controls();
  const std::string initial_what =
      fmt::format("a number or a list of {} numbers (the initial heights α⁰, m)", m);
  const toml::node* initial = r.node("initial");
  if (initial == nullptr) r.fail_missing("initial", initial_what);
  const std::string range = fmt::format("0 <= α <= upper_bound = {}", d.upper_bound);
  if (initial->as_array()) {
    const std::vector<double> values = r.number_list("initial", initial_what);
    if (static_cast<int>(values.size()) != m) r.fail_value("initial", initial_what);
    for (std::size_t i = 0; i < values.size(); ++i)
      if (!(values[i] >= 0 && values[i] <= d.upper_bound)) r.fail_entry("initial", i, range);
    body.initial_design = Eigen::Map<const Eigen::VectorXd>(values.data(), m);
  } else {
    const double value = r.required_number("initial", initial_what);
    if (!(value >= 0 && value <= d.upper_bound)) r.fail_value("initial", range);
    body.initial_design = Eigen::VectorXd::Constant(m, value);
  }

  if (auto c1 = r.optional_number("slope_bound")) {
    if (!(*c1 > 0)) r.fail_value("slope_bound", "slope_bound > 0 (omit it for no slope bound)");
    d.slope_bound = c1;
  }
  if (auto c2 = r.optional_number("volume")) {
    // meas Ω(α) = A·(height − mean of G_α) and 0 <= G_α <= C0 (convex-hull property,
    // docs/theory/problem.md §2), so only this interval is reachable; outside it Υ is empty (the
    // trap of the thesis' printed formula, docs/theory/problem.md §6).
    const double base = dim == 2 ? g.a : g.a * g.b;
    const double lo = base * (g.height - d.upper_bound);
    const double hi = base * g.height;
    if (!(*c2 >= lo && *c2 <= hi))
      r.fail_value("volume", fmt::format("{} <= volume <= {} (the {} reachable with 0 <= α <= C0: "
                                         "{}·(height − C0) to {}·height)",
                                         lo, hi, dim == 2 ? "area" : "volume",
                                         dim == 2 ? "a" : "a·b", dim == 2 ? "a" : "a·b"));
    d.volume = c2;
  }
  if (auto s = read_enum(r, "slope_scaling", shape::kSlopeScalingNames)) d.slope_scaling = *s;

  // friction_orientation (docs/theory/friction-design.md): the law's orientation φ is a design
  // variable too, within [orientation_lower_deg, orientation_upper_deg]; the law itself is checked
  // once the [contact] table is read (study::OrientationDesign).
  const bool orientation = r.optional_bool("friction_orientation").value_or(false);
  const std::optional<double> lower = r.optional_number("orientation_lower_deg");
  const std::optional<double> upper = r.optional_number("orientation_upper_deg");
  if (!orientation) {
    if (lower) r.fail("orientation_lower_deg", "orientation_lower_deg without friction_orientation = true; expected "
                                               "friction_orientation = true or no orientation bounds");
    if (upper) r.fail("orientation_upper_deg", "orientation_upper_deg without friction_orientation = true; expected "
                                               "friction_orientation = true or no orientation bounds");
    return;
  }
  if (!lower) r.fail_missing("orientation_lower_deg", "the lower bound on the law's orientation φ, degrees");
  if (!upper) r.fail_missing("orientation_upper_deg", "the upper bound on the law's orientation φ, degrees");
  if (!(std::abs(*lower) <= 360.0)) r.fail_value("orientation_lower_deg", "an angle in degrees in [−360, 360]");
  if (!(std::abs(*upper) <= 360.0)) r.fail_value("orientation_upper_deg", "an angle in degrees in [−360, 360]");
  if (!(*lower < *upper))
    r.fail_value("orientation_upper_deg", fmt::format("orientation_upper_deg > orientation_lower_deg = {}", *lower));
  body.friction_orientation = study::OrientationDesignDefinition{*lower * std::numbers::pi / 180.0,
                                                                 *upper * std::numbers::pi / 180.0};
}

// [contact.friction] as the case spells it, and the law it defines.
struct Friction {
  FrictionKind kind = FrictionKind::kNone;
  contact::FrictionLaw law = contact::FrictionLaw::disc(0.0);
  std::size_t num_vertices = 0;  ///< 3D "polygon": the length of mu_vertices
};

// The law of a kind and its coefficients (docs/theory/state-problem.md §3, "Friction sets"); the
// law validates convexity itself, and its message gets the table's name.
Friction read_friction(const TableReader& r, int dim) {
  Friction f;
  const std::string kinds = dim == 2
                                ? "none, isotropic, polygon"
                                : "none, isotropic, polygon, ellipse, ellipse_exact, disc_exact";
  const std::string kind_text = r.required_string("kind", fmt::format("one of {}", kinds));
  const std::optional<FrictionKind> kind = kFrictionKindNames.find(kind_text);
  const bool kind_in_2d = kind == FrictionKind::kNone || kind == FrictionKind::kIsotropic ||
                          kind == FrictionKind::kPolygon;
  if (!kind || (dim == 2 && !kind_in_2d))
    r.fail_value("kind", fmt::format("one of {} in {}", kinds, dim_name(dim)));
  f.kind = *kind;

  // The keys each kind uses; a key another kind would use is an error, not silently ignored.
  std::vector<std::string_view> used;
  switch (f.kind) {
    case FrictionKind::kNone:
      used = {"kind"};
      break;
    case FrictionKind::kIsotropic:
      used = dim == 2 ? std::vector<std::string_view>{"kind", "mu"}
                      : std::vector<std::string_view>{"kind", "mu", "n"};
      break;
    case FrictionKind::kPolygon:
      used = dim == 2 ? std::vector<std::string_view>{"kind", "mu_plus", "mu_minus"}
                      : std::vector<std::string_view>{"kind", "mu_vertices", "n"};
      break;
    case FrictionKind::kEllipse:
      used = {"kind", "mu_x", "mu_y", "n"};
      break;
    case FrictionKind::kEllipseExact:
      used = {"kind", "mu_x", "mu_y"};
      break;
    case FrictionKind::kDiscExact:
      used = {"kind", "mu"};
      break;
  }
  // Every law but "none" may be turned in the tangent plane (2D: only by 0, checked below).
  if (f.kind != FrictionKind::kNone) used.push_back("orientation_deg");
  for (auto&& [key, value] : r.table()) {
    if (std::find(used.begin(), used.end(), key.str()) != used.end()) continue;
    std::string list;
    for (std::string_view u : used) list += (list.empty() ? "" : ", ") + std::string(u);
    r.fail(key.str(),
           fmt::format("{} = {} is not used by kind = \"{}\" in {}; that kind "
                       "takes {}",
                       r.field(key.str()), describe(value), kind_text, dim_name(dim), list));
  }

  const auto coefficient = [&](std::string_view key, std::string_view meaning) {
    const double mu = r.required_number(key, fmt::format("a number >= 0 ({})", meaning));
    if (!(mu >= 0 && mu <= kMaxFriction)) r.fail_value(key, fmt::format("0 <= {} <= {}", key, kMaxFriction));
    return mu;
  };
  const auto sides = [&]() -> std::optional<int> {
    auto n = r.optional_int("n");
    if (n && (*n < 3 || *n > kMaxPolygonSides))
      r.fail_value("n", fmt::format("3 <= n <= {} (polygon sides; use disc_exact or ellipse_exact for the exact set)",
                                    kMaxPolygonSides));
    return n;
  };

  using contact::FrictionLaw;
  // The law validates convexity and coefficients itself; its message gets the table's name.
  const auto checked = [&](auto build) -> FrictionLaw {
    try {
      return build();
    } catch (const InvalidInput& e) {
      r.fail("kind", fmt::format("{}: {}", r.path(), e.what()));
    }
  };
  {
    switch (f.kind) {
      case FrictionKind::kNone:
        f.law = dim == 2 ? FrictionLaw::interval(0.0, 0.0) : FrictionLaw::disc(0.0);
        break;
      case FrictionKind::kIsotropic: {
        const double mu = coefficient("mu", "the friction coefficient");
        const int n = dim == 2 ? 0 : sides().value_or(kDefaultPolygonSides);
        f.law = checked([&] { return dim == 2 ? FrictionLaw::interval(mu, mu) : FrictionLaw::regular_polygon(mu, n); });
        break;
      }
      case FrictionKind::kDiscExact:
        f.law = checked([mu = coefficient("mu", "the friction coefficient")] { return FrictionLaw::disc(mu); });
        break;
      case FrictionKind::kPolygon:
        if (dim == 2) {
          const double mu_plus = coefficient("mu_plus", "the coefficient for slip in +x1");
          const double mu_minus = coefficient("mu_minus", "the coefficient for slip in −x1");
          f.law = checked([&] { return FrictionLaw::interval(mu_minus, mu_plus); });
        } else {
          const std::string what = fmt::format("a list of 3 to {} numbers >= 0 (the coefficient of each vertex)",
                                               kMaxPolygonSides);
          std::vector<double> mu_vertices = r.number_list("mu_vertices", what);
          if (mu_vertices.size() < 3 || mu_vertices.size() > static_cast<std::size_t>(kMaxPolygonSides))
            r.fail_value("mu_vertices", what);
          for (std::size_t i = 0; i < mu_vertices.size(); ++i)
            if (!(mu_vertices[i] >= 0 && mu_vertices[i] <= kMaxFriction))
              r.fail_entry("mu_vertices", i, fmt::format("0 <= mu_vertices[i] <= {}", kMaxFriction));
          if (const std::optional<int> n = sides(); n && *n != static_cast<int>(mu_vertices.size()))
            r.fail_value("n", fmt::format("n = the length of mu_vertices ({}), or omit n", mu_vertices.size()));
          f.num_vertices = mu_vertices.size();
          f.law = checked([&] { return FrictionLaw::polygon(std::move(mu_vertices)); });
        }
        break;
      case FrictionKind::kEllipse:
      case FrictionKind::kEllipseExact: {
        const double mu_x = coefficient("mu_x", "the coefficient along x1");
        const double mu_y = coefficient("mu_y", "the coefficient along x2");
        const int n = f.kind == FrictionKind::kEllipse ? sides().value_or(kDefaultPolygonSides) : 0;
        f.law = checked([&] {
          return f.kind == FrictionKind::kEllipse ? FrictionLaw::ellipse_polygon(mu_x, mu_y, n)
                                                  : FrictionLaw::ellipse(mu_x, mu_y);
        });
        break;
      }
    }
  }
  // orientation_deg: the law turned counter-clockwise in the foundation's tangent plane, so
  // μ(θ) becomes μ(θ − φ) (FrictionLaw::rotated).
  if (const std::optional<double> degrees = r.optional_number("orientation_deg")) {
    if (!(std::abs(*degrees) <= 360.0))
      r.fail_value("orientation_deg", "an angle in degrees, −360 <= orientation_deg <= 360");
    if (dim == 2 && *degrees != 0.0)
      r.fail_value("orientation_deg",
                   "0 in 2D (the tangent space of a 2D contact is a line; for a direction-dependent 2D law "
                   "give mu_plus and mu_minus)");
    f.law = f.law.rotated(*degrees * std::numbers::pi / 180.0);
  }
  return f;
}
// [contact] and [contact.friction]: the law; the solver options come from [solver].
Friction read_contact(const TableReader& r, int dim, std::string_view origin) {
  if (const std::optional<std::string> law = r.optional_string("law"); law && *law != "coulomb")
    r.fail_value("law", "one of coulomb");
  if (const toml::table* friction = r.optional_table("friction"))
    return read_friction(
        TableReader(*friction, r.field("friction"), origin,
                    {"kind", "mu", "n", "mu_vertices", "mu_x", "mu_y", "mu_plus", "mu_minus", "orientation_deg"}),
        dim);
  return {FrictionKind::kNone, dim == 2 ? contact::FrictionLaw::interval(0.0, 0.0) : contact::FrictionLaw::disc(0.0)};
}

// Solver limits (docs/case-format.md, "[solver]"): a relative tolerance below the
// double precision floor cannot be met, so with a large iteration cap a solve would run for
// hours before reporting the cap; both are bounded. [solver.coulomb] and [solver.qp] override
// the Coulomb fixed point's and the Tresca QP's own defaults (absent keys keep them).
constexpr double kMinRelativeTolerance = 1e-15;
template <class SolverOptions>
void read_iterative_solver(const TableReader& r, int max_iterations_bound, SolverOptions& options) {
  if (const std::optional<int> n = r.optional_int("max_iterations")) {
    if (*n < 1 || *n > max_iterations_bound)
      r.fail_value("max_iterations", fmt::format("1 <= max_iterations <= {}", max_iterations_bound));
    options.max_iterations = *n;
  }
  if (const std::optional<double> tol = r.optional_number("relative_tolerance")) {
    if (!(*tol >= kMinRelativeTolerance && *tol < 1))
      r.fail_value("relative_tolerance",
                   fmt::format("{:g} <= relative_tolerance < 1 (below it double precision cannot meet it)",
                               kMinRelativeTolerance));
    options.relative_tolerance = *tol;
  }
}

// [solver] into the Coulomb solver's options (read, and validated, with or without [contact]).
contact::CoulombSolver::Options read_solver(const TableReader& r, std::string_view origin) {
  contact::CoulombSolver::Options s;
  const auto sub = [&](std::string_view key, std::initializer_list<std::string_view> keys) {
    const toml::table* t = r.optional_table(key);
    return t ? std::optional<TableReader>(std::in_place, *t, r.field(key), origin, keys)
             : std::nullopt;
  };
  if (auto coulomb = sub("coulomb", {"max_iterations", "relative_tolerance", "method"}))
    read_iterative_solver(*coulomb, 10'000, s);
  if (auto qp = sub("qp", {"max_iterations", "relative_tolerance"})) read_iterative_solver(*qp, 1'000'000, s.tresca);
  // [solver.fem] is reserved: it may appear, but has no keys yet (the direct solver has no
  // options a case should change); the empty key list makes any key an error.
  (void)sub("fem", {});
  return s;
}

// [cost] step and the loading programs a history cost reads (docs/theory/history-adjoint.md;
// study/history.hpp): `step` is "last" (the default) or a 1-based step of the [[program.step]]
// tables — or, with load cases given as programs ([[load_case.step]]), of every case's program (a
// static case is one step). A step or the dissipation on a case without a program is a history
// cost on a one-step case.
void read_cost_history(const TableReader& r, const std::optional<study::LoadingProgramDefinition>& program,
                       study::CostDefinition& c) {
  const bool case_programs = c.load_cases && c.load_cases->has_programs();
  if (program && c.load_cases)
    r.fail("step", "[[program.step]] tables with [[load_case]] tables: the program would apply to no case in "
                   "particular; expected each load case's own [[load_case.step]] tables");
  // The fewest steps a case has: a step beyond it would read a state that case does not have.
  std::size_t steps = program ? program->steps.size() : 0;
  std::string fewest = fmt::format("the case has {} [[program.step]] table{}", steps, steps == 1 ? "" : "s");
  if (case_programs) {
    steps = std::numeric_limits<std::size_t>::max();
    for (std::size_t k = 0; k < c.load_cases->cases.size(); ++k) {
      const study::LoadCaseDefinition& lc = c.load_cases->cases[k];
      if (lc.num_steps() < steps) {
        steps = lc.num_steps();
        fewest = lc.program ? fmt::format("load_case[{}] \"{}\" has {} [[load_case.step]] table{}", k, lc.name, steps,
                                          steps == 1 ? "" : "s")
                            : fmt::format("load_case[{}] \"{}\" is a static load: one step", k, lc.name);
      }
    }
  }
  const bool history = program.has_value() || case_programs;
  const std::string expectation =
      history ? fmt::format("\"last\" or an integer step in [1, {}] ({})", steps, fewest)
              : std::string("no step: the case has no [[program.step]] or [[load_case.step]] tables (a history cost on "
                            "a one-step case)");
  if (const toml::node* step = r.node("step")) {
    if (!history) r.fail_value("step", expectation);
    if (step->is_string()) {
      if (step->value<std::string>().value_or("") != "last") r.fail_value("step", expectation);
      c.step = 0;
    } else if (step->is_integer()) {
      const std::int64_t k = step->value<std::int64_t>().value_or(0);
      if (k < 1 || k > static_cast<std::int64_t>(steps)) r.fail_value("step", expectation);
      c.step = static_cast<int>(k);
    } else {
      r.fail_value("step", expectation);
    }
  }
  if (c.kind == cost::CostKind::kDissipation && !history)
    r.fail_value("kind", "a cost of one state (the case has no [[program.step]] or [[load_case.step]] tables: "
                         "\"dissipation\" is a history cost on a one-step case)");
  if (history) {
    if (c.kind == cost::CostKind::kCompliance)
      r.fail_value("kind", "a contact cost or \"dissipation\" with a loading program (the compliance reads the case "
                           "file's own loads, not a step's)");
    if (c.kind == cost::CostKind::kDissipation && r.has("step"))
      r.fail_value("step", "no step for \"dissipation\" (it reads every step of the program)");
  }
  if (program) c.program = std::make_shared<const study::LoadingProgramDefinition>(*program);
}

// [cost] into the study's cost definition (docs/theory/costs.md). `dim` checks the traction target.
study::CostDefinition read_cost(const TableReader& r, int dim) {
  using cost::CostKind;
  study::CostDefinition c;
  const std::string kind_what = fmt::format("one of {}", cost::kCostKindNames.spellings());
  (void)r.required_string("kind", kind_what);
  c.kind = *read_enum(r, "kind", cost::kCostKindNames);
  // The pressure norm's default exponent differs from the force power's (thesis: 4).
  if (c.kind == CostKind::kPressureNorm) c.exponent = 8.0;
  if (c.kind == CostKind::kTargetPressure) {
    const toml::node* target = r.node("target");
    if (target == nullptr) r.fail_missing("target", "a target pressure [Pa] or \"initial_mean\"");
    if (target->is_string()) {
      if (target->value<std::string>().value_or("") != "initial_mean")
        r.fail_value("target", "a number (pressure in Pa) or \"initial_mean\"");
      // NaN: the initial total normal force spread as a uniform pressure (study::CostDefinition).
      c.target_pressure = std::numeric_limits<double>::quiet_NaN();
    } else {
      c.target_pressure = r.required_number("target", "a target pressure [Pa] or \"initial_mean\"");
      if (!(c.target_pressure >= 0)) r.fail_value("target", "target >= 0");
    }
  } else if (c.kind == CostKind::kTractionUniformity) {
    // Optional: "mean" (the default), "initial_mean" or the target traction [Pa], dim − 1 numbers.
    if (const toml::node* target = r.node("target"); target != nullptr) {
      if (target->is_string()) {
        const std::string word = target->value<std::string>().value_or("");
        if (word != "mean" && word != "initial_mean")
          r.fail_value("target", "\"mean\", \"initial_mean\" or a list of dim − 1 tangential tractions [Pa]");
        c.target_traction_initial_mean = word == "initial_mean";
      } else {
        const std::vector<double> t = r.number_list("target", "the target tangential traction [Pa]");
        if (t.size() != static_cast<std::size_t>(dim - 1))
          r.fail("target", fmt::format("cost.target has {} components; expected {} (the tangential traction [Pa] of "
                                       "a {}D body) or \"mean\"",
                                       t.size(), dim - 1, dim));
        c.target_traction = Eigen::Map<const Eigen::VectorXd>(t.data(), static_cast<Eigen::Index>(t.size()));
      }
    }
  } else if (r.has("target")) {
    r.fail_value("target", "no target for this kind (only target_pressure and traction_uniformity have one)");
  }
  if (const std::optional<double> exponent = r.optional_number("exponent")) {
    if (c.kind != CostKind::kNormalForcePower && c.kind != CostKind::kPressureNorm)
      r.fail_value("exponent", "no exponent for this kind");
    if (!(*exponent >= 2)) r.fail_value("exponent", "exponent >= 2");
    c.exponent = *exponent;
  }
  if (const std::optional<double> smoothing = r.optional_number("smoothing")) {
    if (c.kind != CostKind::kTotalSlip) r.fail_value("smoothing", "no smoothing for this kind");
    if (!(*smoothing > 0)) r.fail_value("smoothing", "smoothing > 0");
    c.smoothing = *smoothing;
  }
  return c;
}

// [optimization]: overrides of the bundle trust options (the study's defaults otherwise).
void read_optimization(const TableReader& r, optim::BundleTrust::Options& o) {
  if (const std::optional<int> n = r.optional_int("max_iterations")) {
    if (*n < 1) r.fail_value("max_iterations", "max_iterations >= 1");
    o.max_iterations = *n;
  }
  if (const std::optional<int> n = r.optional_int("max_evaluations")) {
    if (*n < 1) r.fail_value("max_evaluations", "max_evaluations >= 1");
    o.max_evaluations = *n;
  }
  if (const std::optional<double> eps = r.optional_number("epsilon")) {
    if (!(*eps > 0)) r.fail_value("epsilon", "epsilon > 0");
    o.epsilon = *eps;
  }
  if (const std::optional<double> t = r.optional_number("max_step_length")) {
    if (!(*t > 0)) r.fail_value("max_step_length", "max_step_length > 0");
    o.max_step_length = *t;
  }
  if (const std::optional<int> n = r.optional_int("bundle_size")) {
    if (*n < 3) r.fail_value("bundle_size", "bundle_size >= 3");
    o.max_bundle_size = *n;
  }
  // The opt-in diagonal variable metric of the proximal term (docs/optim.md, "Variable metric").
  if (const std::optional<bool> b = r.optional_bool("variable_metric")) o.variable_metric = *b;
  // Worst-case load cases: the other cases' cuts in the bundle (docs/optim.md, "Cuts of the
  // pieces of a max"); off saves K − 1 adjoints per evaluation.
  if (const std::optional<bool> b = r.optional_bool("case_cuts")) o.use_piece_cuts = *b;
  // The default confirmation of a stop in the point's units when they spread by more than
  // point_units_spread (docs/optim.md, "Confirmation in the point's units").
  if (const std::optional<bool> b = r.optional_bool("confirm_in_point_units")) o.confirm_in_point_units = *b;
  if (const std::optional<double> k = r.optional_number("point_units_spread")) {
    if (!(*k >= 1.0) || !std::isfinite(*k)) r.fail_value("point_units_spread", "point_units_spread >= 1 (finite)");
    o.point_units_spread = *k;
  }
}

// 255 − len(".") − len("_iter") − 10 digits − len(".vtu") − len(".XXXXXX.tmp").
constexpr std::size_t kMaxOutputNameBytes = 255 - 1 - 5 - 10 - 4 - 11;

OutputSpec read_output(const TableReader& r, std::string default_name) {
  OutputSpec o;
  o.vtk = r.optional_bool("vtk").value_or(true);
  if ((o.every = r.optional_int("every").value_or(1)) < 1) r.fail_value("every", "every >= 1");
  o.name = r.optional_string("name").value_or(std::move(default_name));
  // The name becomes part of file names: a NUL byte would cut them short (the CSV then
  // overwrote the VTU), a '/' would leave the directory, "." and ".." are directories.
  const bool control = std::any_of(o.name.begin(), o.name.end(),
                                   [](char ch) { return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f; });
  if (o.name.empty() || control || o.name.find_first_of("/\\") != std::string::npos || o.name == "." ||
      o.name == "..")
    r.fail_value("name", "a non-empty file name without '/', '\\' or control characters (NUL, newline, ...)");
  // The longest file made of the name must fit a file name (NAME_MAX = 255 bytes on Linux):
  // the temporary of a series file, "." + name + "_iter" + 10 digits + ".vtu" + ".XXXXXX.tmp".
  if (o.name.size() > kMaxOutputNameBytes)
    r.fail_value("name", fmt::format("at most {} bytes (it has {}), so that its longest output file name "
                                     "(\".NAME_iterK.vtu.XXXXXX.tmp\") fits the file system's 255",
                                     kMaxOutputNameBytes, o.name.size()));
  return o;
}


// A traction component on a face that a [[dirichlet]] table fixes in that component does no
// work (the reaction absorbs it): it is always a mistake in the case, so it is refused.
void check_loads_on_fixed_faces(const CaseDescription& c, int dim,
                                const std::map<std::pair<std::string, int>, std::size_t>& fixed_by) {
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

// With contact, the unknowns above the contact surface form the leading block of the
// stiffness (contact unknowns are ordered last, docs/contact.md): with one cell layer and a
// fully fixed top that block is empty and there is no elastic body left to solve for.
void check_free_unknowns(const CaseDescription& c, int dim,
                         const std::map<std::pair<std::string, int>, std::size_t>& fixed_by) {
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

// The canonical text of a TOML value for CaseDescription::problem_settings.
std::string canonical(const toml::node& node) {
  if (const auto* i = node.as_integer()) return format_number(static_cast<double>(i->get()));
  if (const auto* x = node.as_floating_point()) return format_number(x->get());
  if (const auto* b = node.as_boolean()) return b->get() ? "true" : "false";
  if (const auto* t = node.as_string()) return "\"" + t->get() + "\"";
  if (const auto* a = node.as_array()) {
    std::string out = "[";
    for (std::size_t i = 0; i < a->size(); ++i) out += (i ? ", " : "") + canonical(*a->get(i));
    return out + "]";
  }
  std::ostringstream other;  // dates and times
  node.visit([&](const auto& v) { other << v; });
  return other.str();
}

void flatten(const toml::node& node, const std::string& key, std::map<std::string, std::string>& out) {
  if (const auto* table = node.as_table()) {
    for (auto&& [k, v] : *table) flatten(v, key.empty() ? std::string(k.str()) : key + "." + std::string(k.str()), out);
    if (table->empty()) out[key] = "{}";
    return;
  }
  if (const auto* array = node.as_array(); array && array->is_array_of_tables()) {
    for (std::size_t i = 0; i < array->size(); ++i) flatten(*array->get(i), fmt::format("{}[{}]", key, i), out);
    return;
  }
  out[key] = canonical(node);
}

std::map<std::string, std::string> problem_settings(const toml::table& root) {
  std::map<std::string, std::string> out;
  for (auto&& [key, value] : root)
    if (key.str() != "optimization" && key.str() != "output") flatten(value, std::string(key.str()), out);
  return out;
}

}  // namespace

CaseDescription parse_case(std::string_view toml_text, std::string_view origin_name) {
  const std::string origin(origin_name);
  toml::table root;
  try {
    root = toml::parse(detail::without_bom(toml_text), origin_name);
  } catch (const toml::parse_error& e) {
    throw InvalidInput(fmt::format("{}:{}:{}: TOML syntax error: {}", origin, e.source().begin.line,
                                   e.source().begin.column, e.description()));
  }
  const TableReader top(root, "", origin,
                        {"geometry", "mesh", "material", "load", "dirichlet", "design", "contact",
                         "solver", "cost", "optimization", "output", "identification",
                         // friction experiments (case_program_section.hpp)
                         "force", "constraint", "program", "experiment", "foundation",
                         // load cases (case_load_case_section.hpp)
                         "load_case", "study",
                         // loading plates (case_plate_section.hpp)
                         "plate"});
  const auto table = [&](std::string_view key, std::initializer_list<std::string_view> keys) {
    const toml::table* t = top.optional_table(key);
    if (t == nullptr) top.fail_missing(key, fmt::format("a table [{}]", key));
    return TableReader(*t, std::string(key), origin, keys);
  };

  CaseDescription c;
  c.origin = origin;
  study::BodyDefinition& body = c.body;
  // An imported body ([mesh] file = ..., docs/meshes.md): the geometry's extents come from its
  // mesh.
  const bool imported = detail::names_mesh_file(root);
  Geometry geometry;
  const mesh::Mesh* imported_mesh = nullptr;
  if (imported) {
    const TableReader g = table("geometry", {"dim"});
    geometry.dim = g.required_int("dim", "2 or 3");
    if (geometry.dim != 2 && geometry.dim != 3) g.fail_value("dim", "2 or 3");
    // The design moves the patch along the foundation's normal (docs/meshes.md, "The design on a
    // patch"), so a tilted [foundation] sets the motion's frame and the patch chart's plane too.
    mesh::PlaneFrame design_frame = mesh::PlaneFrame::standard(geometry.dim);
    if (const toml::table* foundation = top.optional_table("foundation"))
      design_frame = detail::read_foundation(TableReader(*foundation, "foundation", origin, {"normal", "offset", "axis1"}),
                                             geometry.dim)
                         .frame;
    detail::ImportedBody ib = detail::read_imported_mesh(table("mesh", {"file", "size", "contact", "patch", "extension"}),
                                                         geometry.dim, origin, design_frame);
    geometry.a = ib.a;
    geometry.b = ib.b;
    geometry.height = ib.height;
    body.contact_surface = ib.contact_surface;
    body.imported_mesh = std::move(ib.definition);
    imported_mesh = body.imported_mesh->reference.get();
  } else {
    geometry = read_geometry(table("geometry", {"dim", "a", "b", "height"}));
  }
  const int dim = geometry.dim;
  body.height = geometry.height;
  if (!imported) body.resolution = read_mesh(table("mesh", {"cells", "grading", "growth", "refine_box", "vertical_grading", "fine_depth", "vertical_growth"}), geometry);
  body.material = read_material(table("material", {"young", "poisson", "model"}), dim);

  if (const toml::array* loads = top.optional_table_array("load", detail::kMaxBodyTables))
    for (std::size_t i = 0; i < loads->size(); ++i)
      body.tractions.push_back(
          read_load(TableReader(*loads->get(i)->as_table(), fmt::format("load[{}]", i), origin,
                                {"face", "boundary", "traction"}),
                    dim, body.material.young, imported_mesh));

  const toml::array* dirichlet = top.optional_table_array("dirichlet", detail::kMaxBodyTables);
  // Without [[dirichlet]] a body floats: only contact and friction can hold it
  // (docs/experiments.md §5; study::ElasticBody solves it with the kernel-aware dual).
  const toml::array no_dirichlet;
  if ((dirichlet == nullptr || dirichlet->empty()) && top.optional_table("contact") == nullptr &&
      top.optional_table_array("constraint", detail::kMaxBodyTables) == nullptr)
    top.fail_missing("dirichlet",
                     "at least one [[dirichlet]] table (a body without a "
                     "Dirichlet part and without [contact] has rigid-body modes)");
  if (dirichlet == nullptr) dirichlet = &no_dirichlet;
  // (face, component) -> index of the [[dirichlet]] entry that fixes it first.
  std::map<std::pair<std::string, int>, std::size_t> fixed_by;
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
  detail::read_program_sections(top, origin, dim, c);
  detail::read_plate_sections(top, origin, dim, imported_mesh, c);

  read_design(table("design", {"control_points", "initial", "upper_bound", "slope_bound", "volume", "slope_scaling",
                               "friction_orientation", "orientation_lower_deg", "orientation_upper_deg"}),
              geometry, body);

  std::optional<Friction> friction;
  if (const toml::table* contact = top.optional_table("contact"))
    friction = read_contact(TableReader(*contact, "contact", origin, {"law", "friction"}), dim, origin);
  contact::CoulombSolver::Options coulomb;
  if (const toml::table* solver = top.optional_table("solver")) {
    coulomb = read_solver(TableReader(*solver, "solver", origin, {"coulomb", "qp", "fem", "engine", "petsc_options", "newton"}), origin);
    detail::read_solver_engine(TableReader(*solver, "solver", origin, {"coulomb", "qp", "fem", "engine", "petsc_options", "newton"}), origin, body.engine);
    detail::read_coulomb_method(TableReader(*solver, "solver", origin, {"coulomb", "qp", "fem", "engine", "petsc_options", "newton"}), origin, body.engine, coulomb);
  }
  if (friction) {
    study::ContactDefinition contact_definition;
    contact_definition.law = friction->law;
    contact_definition.coulomb = coulomb;
    if (const toml::table* foundation = top.optional_table("foundation"))
      contact_definition.foundation =
          detail::read_foundation(TableReader(*foundation, "foundation", origin, {"normal", "offset", "axis1"}), dim);
    body.contact = std::move(contact_definition);
  } else if (top.optional_table("foundation")) {
    throw InvalidInput(fmt::format("{}: [foundation] needs a [contact] table (a body without contact never meets "
                                   "the foundation); expected [contact] or no [foundation]",
                                   origin));
  }
  if (!imported) check_free_unknowns(c, dim, fixed_by);  // the structured grid's layers
  if (body.friction_orientation) {
    // The law must have an orientation that matters and φ⁰ must lie within the bounds.
    if (!body.contact)
      throw InvalidInput(fmt::format("{}: design.friction_orientation = true needs a [contact] table with an "
                                     "anisotropic 3D friction law",
                                     origin));
    try {
      (void)study::OrientationDesign(*body.friction_orientation, body.contact->law, body.admissible.upper_bound);
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{}: {}", origin, e.what()));
    }
    if (body.engine.kind == study::StateEngine::kPetsc)
      throw InvalidInput(fmt::format("{}: design.friction_orientation = true: the PETSc engine keeps its law fixed; "
                                     "expected solver.engine = \"direct\"",
                                     origin));
  }

  std::optional<TableReader> cost_reader;
  if (const toml::table* cost = top.optional_table("cost")) {
    if (!body.contact)
      throw InvalidInput(fmt::format("{}: [cost] needs a [contact] table: every cost reads the contact state", origin));
    cost_reader.emplace(*cost, "cost", origin, std::initializer_list<std::string_view>{"kind", "target", "exponent", "smoothing", "step"});
    c.cost = read_cost(*cost_reader, dim);
  }
  detail::read_load_case_sections(top, origin, c);
  if (cost_reader) read_cost_history(*cost_reader, c.program, *c.cost);
  c.optimization = study::default_study_options(body);
  if (const toml::table* optimization = top.optional_table("optimization"))
    read_optimization(TableReader(*optimization, "optimization", origin,
                                  {"max_iterations", "max_evaluations", "epsilon", "max_step_length", "bundle_size",
                                   "variable_metric", "case_cuts", "confirm_in_point_units",
                                   "point_units_spread"}),
                      c.optimization);

  detail::read_identification_section(top, origin, c, friction ? kFrictionKindNames.name(friction->kind) : "",
                                      friction ? friction->num_vertices : 0);

  // Default output name: the file stem, or the case directory's name for the
  // cases*/<name>/case.toml layout (every case file there is called case.toml).
  const std::filesystem::path origin_path(origin);
  std::string default_name = origin_path.stem() == "case" && origin_path.has_parent_path() &&
                                     !origin_path.parent_path().filename().empty()
                                 ? origin_path.parent_path().filename().string()
                                 : origin_path.stem().string();
  if (const toml::table* output = top.optional_table("output"))
    c.output = read_output(TableReader(*output, "output", origin, {"vtk", "every", "name"}),
                           std::move(default_name));
  else
    c.output.name = std::move(default_name);
  body.name = c.output.name;
  c.problem_settings = problem_settings(root);
  // The mesh file by its resolved name, not as written: the same file named relative to the
  // user's case and absolutely in the run directory's copy is the same problem.
  if (c.body.imported_mesh) c.problem_settings["mesh.file"] = "\"" + c.body.imported_mesh->file.string() + "\"";
  return c;
}

const study::CostDefinition& CaseDescription::required_cost() const {
  if (!cost)
    throw InvalidInput(fmt::format("{}: no [cost] table; expected one with kind = one of {}", origin,
                                   cost::kCostKindNames.spellings()));
  return *cost;
}

const IdentificationSetup& CaseDescription::required_identification() const {
  if (!identification) throw InvalidInput(fmt::format("{}: the case has no [identification] table", origin));
  return *identification;
}

CaseDescription load_case(const std::filesystem::path& path) { return load_case(path, path.string()); }

CaseDescription load_case(const std::filesystem::path& path, std::string_view origin_name) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InvalidInput(
        fmt::format("{}: case file not found (or not a regular file)", path.string()));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidInput(fmt::format("{}: case file could not be opened for reading", path.string()));
  std::ostringstream text;
  // operator<< of an empty stream buffer sets failbit: an empty file is reported as such.
  if (in.peek() == std::ifstream::traits_type::eof()) {
    if (in.bad()) throw InvalidInput(fmt::format("{}: case file could not be read", path.string()));
    throw InvalidInput(fmt::format("{}: the case file is empty; expected a TOML case (docs/case-format.md)",
                                   path.string()));
  }
  text << in.rdbuf();
  if (in.bad() || !text) throw InvalidInput(fmt::format("{}: case file could not be read", path.string()));
  return parse_case(text.str(), origin_name);
}

}  // namespace frictopt::io
