// SPDX-License-Identifier: MIT
// What the case file's table readers share (docs/case-format.md): the geometry every later table
// reads, the names of the dimension and of the structured box's faces, a face, a vector of dim
// numbers, an enumeration by its spellings, and a required table. Private to io.
#pragma once

#include <Eigen/Core>
#include <fmt/format.h>

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "frictopt/core/enum_table.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

// [geometry]: the box (0,a)×(0,b)×(G_α, height) (docs/theory/problem.md §2); its numbers go into
// the Bézier shape (a, b) and the body (height).
struct Geometry {
  int dim = 2;
  double a = 0.0, b = 0.0, height = 0.0;
};

/// "2D" or "3D".
std::string_view dim_name(int dim);
/// The structured box's faces that may carry loads and Dirichlet conditions, as a list.
std::string faces_for(int dim);
/// A face of the structured box by its boundary-set name ("left", ..., "top"; the bottom is Γ_c).
std::string read_face(const TableReader& r, int dim);
/// A list of exactly `dim` numbers at `key`; `meaning` says what it is ("traction, N/m²").
Eigen::VectorXd read_dim_vector(const TableReader& r, std::string_view key, int dim, std::string_view meaning);

/// The value at `key` by its spelling in `table` (nullopt when absent); throws naming the spellings.
template <class Enum, std::size_t N>
std::optional<Enum> read_enum(const TableReader& r, std::string_view key,
                              const frictopt::detail::EnumTable<Enum, N>& table) {
  const std::optional<std::string> text = r.optional_string(key);
  if (!text) return std::nullopt;
  const std::optional<Enum> value = table.find(*text);
  if (!value) r.fail_value(key, fmt::format("one of {}", table.spellings()));
  return value;
}

/// The table [key] of the root `top`, read with its allowed keys; "key is missing" when absent.
TableReader required_table(const TableReader& top, std::string_view key, std::string_view origin,
                           std::initializer_list<std::string_view> keys);

}  // namespace frictopt::io::detail
