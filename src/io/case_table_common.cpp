// SPDX-License-Identifier: MIT
#include "case_table_common.hpp"

#include "frictopt/core/error.hpp"
#include "frictopt/mesh/face.hpp"

namespace frictopt::io::detail {

std::string_view dim_name(int dim) { return dim == 2 ? "2D" : "3D"; }

std::string faces_for(int dim) {
  return dim == 2 ? "left, right, top" : "left, right, front, back, top";
}

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

Eigen::VectorXd read_dim_vector(const TableReader& r, std::string_view key, int dim,
                                std::string_view meaning) {
  const std::string what =
      fmt::format("a list of {} numbers ({}) in {}", dim, meaning, dim_name(dim));
  const std::vector<double> v = r.number_list(key, what);
  if (static_cast<int>(v.size()) != dim) r.fail_value(key, what);
  return Eigen::Map<const Eigen::VectorXd>(v.data(), dim);
}

TableReader required_table(const TableReader& top, std::string_view key, std::string_view origin,
                           std::initializer_list<std::string_view> keys) {
  const toml::table* t = top.optional_table(key);
  if (t == nullptr) top.fail_missing(key, fmt::format("a table [{}]", key));
  return TableReader(*t, std::string(key), origin, keys);
}

}  // namespace frictopt::io::detail
