// SPDX-License-Identifier: MIT
#include "case_contact_section.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "case_table_common.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::io::detail {
namespace {

// Default polygon size for the 3D isotropic and elliptic laws: the thesis' 3D runs use
// n-gons, and n = 16 keeps the polygon within 2% of the disc (1 − cos(π/16) ≈ 0.019).
constexpr int kDefaultPolygonSides = 16;

constexpr int kMaxPolygonSides = 256;               // 1 − cos(π/256) < 1e-4 of the disc

// Physical bounds (docs/case-format.md, "Physical bounds"): beyond them the numbers are
// outside linear elasticity or outside double precision, and the solvers would fail with
// messages that do not name the field.
constexpr double kMaxFriction = 10.0;    // no dry-friction pair comes near

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

}  // namespace

std::optional<Friction> read_contact_section(const TableReader& top, std::string_view origin, int dim) {
  const toml::table* contact = top.optional_table("contact");
  if (contact == nullptr) return std::nullopt;
  return read_contact(TableReader(*contact, "contact", origin, {"law", "friction"}), dim, origin);
}

}  // namespace frictopt::io::detail
