// SPDX-License-Identifier: MIT
#include "case_foundation_section.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "frictopt/core/error.hpp"

namespace frictopt::io::detail {
namespace {

// A direction given by the case: `size` finite numbers, not all zero.
Eigen::VectorXd read_direction(const TableReader& r, std::string_view key, int size, std::string_view meaning) {
  const std::string what = fmt::format("a list of {} numbers, not all zero ({})", size, meaning);
  const std::vector<double> v = r.number_list(key, what);
  if (static_cast<int>(v.size()) != size) r.fail_value(key, what);
  Eigen::VectorXd x(size);
  for (int k = 0; k < size; ++k) {
    if (!std::isfinite(v[static_cast<std::size_t>(k)])) r.fail_entry(key, static_cast<std::size_t>(k), "a finite number");
    x(k) = v[static_cast<std::size_t>(k)];
  }
  if (!(x.norm() > 0.0)) r.fail_value(key, what);
  return x;
}

}  // namespace

contact::Foundation read_foundation(const TableReader& r, int dim) {
  contact::Foundation f;
  const Eigen::VectorXd normal =
      r.table().contains("normal")
          ? read_direction(r, "normal", dim, "the unit normal of the foundation plane, pointing into the body")
          : Eigen::VectorXd::Unit(dim, dim - 1);
  if (const std::optional<double> offset = r.optional_number("offset")) {
    if (!std::isfinite(*offset)) r.fail_value("offset", "a finite distance d [m] (the body lies in n·x >= d)");
    f.offset = *offset;
  }
  Eigen::VectorXd axis1;
  if (r.table().contains("axis1")) {
    if (dim == 2)
      r.fail("axis1", fmt::format("{}: a 2D foundation's tangent is fixed by its normal (t1 = n turned by −90°); "
                                  "expected no axis1 in 2D",
                                  r.field("axis1")));
    axis1 = read_direction(r, "axis1", 3, "the first in-plane axis of the friction law's frame");
  } else if (dim == 3) {
    // Default: e1 projected onto the plane; e2 when the plane is normal to e1.
    const Eigen::Vector3d n = normal.normalized();
    axis1 = std::abs(n(0)) < 1.0 - 1e-8 ? Eigen::VectorXd(Eigen::Vector3d::UnitX()) : Eigen::VectorXd(Eigen::Vector3d::UnitY());
  }
  if (dim == 3) {
    const Eigen::Vector3d n = normal.normalized(), a = Eigen::Vector3d(axis1).normalized();
    // PlaneFrame::from_normal refuses |a − (a·n)n| <= 1e-8|a|: say so with the key.
    if (!((a - a.dot(n) * n).norm() > 1e-8))
      r.fail("axis1", fmt::format("{} = [{}, {}, {}] is parallel to foundation.normal = [{}, {}, {}]; expected an "
                                  "axis with a component in the foundation plane",
                                  r.field("axis1"), axis1(0), axis1(1), axis1(2), normal(0), normal(1), normal(2)));
  }
  try {
    f.frame = mesh::PlaneFrame::from_normal(normal, dim == 3 ? axis1 : Eigen::VectorXd());
  } catch (const InvalidInput& e) {
    r.fail("normal", fmt::format("{}: {}", r.field("normal"), e.what()));
  }
  return f;
}

std::optional<contact::Foundation> read_foundation_section(const TableReader& top, std::string_view origin, int dim) {
  const toml::table* table = top.optional_table("foundation");
  if (table == nullptr) return std::nullopt;
  return read_foundation(TableReader(*table, "foundation", origin, {"normal", "offset", "axis1"}), dim);
}

}  // namespace frictopt::io::detail
