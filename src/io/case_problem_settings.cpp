// SPDX-License-Identifier: MIT
#include "case_problem_settings.hpp"

#include <fmt/format.h>

#include <sstream>

#include "frictopt/core/validation.hpp"
#include "text_input.hpp"

namespace frictopt::io::detail {
namespace {

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

}  // namespace

std::map<std::string, std::string> problem_settings(const toml::table& root) {
  std::map<std::string, std::string> out;
  for (auto&& [key, value] : root)
    if (key.str() != "optimization" && key.str() != "output") flatten(value, std::string(key.str()), out);
  return out;
}

}  // namespace frictopt::io::detail
