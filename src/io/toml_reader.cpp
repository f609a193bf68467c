// SPDX-License-Identifier: MIT
#include "toml_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "frictopt/core/error.hpp"

namespace frictopt::io::detail {
namespace {

// Lists longer than this are abbreviated in messages; a message should fit on a line or two.
constexpr std::size_t kMaxListedEntries = 8;

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::array:
      return "a list";
    case toml::node_type::table:
      return "a table";
    default:
      return "a date/time";
  }
}

std::size_t edit_distance(std::string_view s, std::string_view t) {
  std::vector<std::size_t> row(t.size() + 1);
  for (std::size_t j = 0; j <= t.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= s.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= t.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (s[i - 1] == t[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[t.size()];
}

}  // namespace

std::string located(std::string_view origin, const toml::node* node, std::string_view message) {
  if (node != nullptr && node->source().begin.line > 0)
    return fmt::format("{}:{}: {}", origin, node->source().begin.line, message);
  return fmt::format("{}: {}", origin, message);
}

std::string describe(const toml::node& node) {
  if (auto s = node.as_string()) return fmt::format("\"{}\"", s->get());
  if (auto i = node.as_integer()) return fmt::format("{}", i->get());
  // fmt's "{}" prints the shortest representation that reads back exactly: 0.6, not 0.59999.
  if (auto f = node.as_floating_point()) return fmt::format("{}", f->get());
  if (auto b = node.as_boolean()) return b->get() ? "true" : "false";
  if (auto a = node.as_array()) {
    std::string out = "[";
    for (std::size_t i = 0; i < a->size() && i < kMaxListedEntries; ++i) {
      if (i > 0) out += ", ";
      out += describe(*a->get(i));
    }
    if (a->size() > kMaxListedEntries) out += ", ...";
    return out + "]";
  }
  return type_name(node);
}

std::string_view closest_key(std::string_view key,
                             std::initializer_list<std::string_view> candidates) {
  // Distance 2 catches transpositions ("heigth") and one-letter slips; beyond that the
  // suggestion is more often noise than help.
  constexpr std::size_t kMaxTypoDistance = 2;
  std::string_view best;
  std::size_t best_distance = kMaxTypoDistance + 1;
  for (std::string_view candidate : candidates) {
    const std::size_t d = edit_distance(key, candidate);
    if (d < best_distance && d < key.size()) {
      best = candidate;
      best_distance = d;
    }
  }
  return best;
}

TableReader::TableReader(const toml::table& table, std::string path, std::string_view origin,
                         std::initializer_list<std::string_view> allowed)
    : table_(table), path_(std::move(path)), origin_(origin) {
  for (auto&& [key, value] : table_) {
    const std::string_view k = key.str();
    if (std::find(allowed.begin(), allowed.end(), k) != allowed.end()) continue;
    std::string expected;
    for (std::string_view a : allowed) {
      if (!expected.empty()) expected += ", ";
      expected += a;
    }
    std::string hint;
    if (const std::string_view guess = closest_key(k, allowed); !guess.empty())
      hint = fmt::format(" (did you mean '{}'?)", guess);
    throw InvalidInput(
        located(origin_, &value,
                fmt::format("unknown key '{}'{}; expected one of {}", field(k), hint, expected)));
  }
}

bool TableReader::has(std::string_view key) const { return table_.contains(key); }

const toml::node* TableReader::node(std::string_view key) const { return table_.get(key); }

std::string TableReader::field(std::string_view key) const {
  return path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key);
}

const toml::node& TableReader::require(std::string_view key, std::string_view what) const {
  const toml::node* n = node(key);
  if (n == nullptr) fail_missing(key, what);
  return *n;
}

void TableReader::fail_type(const toml::node& n, std::string_view field_name,
                            std::string_view expected_type) const {
  throw InvalidInput(located(origin_, &n,
                             fmt::format("{} = {} ({}); expected {}", field_name, describe(n),
                                         type_name(n), expected_type)));
}

double TableReader::to_number(const toml::node& n, std::string_view field_name) const {
  double x = 0.0;
  if (auto i = n.as_integer())
    x = static_cast<double>(i->get());
  else if (auto f = n.as_floating_point())
    x = f->get();
  else
    fail_type(n, field_name, "a number");
  // TOML admits inf and nan; no field of a case has a meaning for them.
  if (!std::isfinite(x))
    throw InvalidInput(
        located(origin_, &n, fmt::format("{} = {}; expected a finite number", field_name, x)));
  return x;
}

int TableReader::to_int(const toml::node& n, std::string_view field_name) const {
  auto i = n.as_integer();
  if (!i) fail_type(n, field_name, "an integer");
  const std::int64_t v = i->get();
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    throw InvalidInput(
        located(origin_, &n,
                fmt::format("{} = {}; expected an integer that fits in 32 bits", field_name, v)));
  return static_cast<int>(v);
}

double TableReader::required_number(std::string_view key, std::string_view what) const {
  return to_number(require(key, what), field(key));
}

std::optional<double> TableReader::optional_number(std::string_view key) const {
  if (const toml::node* n = node(key)) return to_number(*n, field(key));
  return std::nullopt;
}

int TableReader::required_int(std::string_view key, std::string_view what) const {
  return to_int(require(key, what), field(key));
}

std::optional<int> TableReader::optional_int(std::string_view key) const {
  if (const toml::node* n = node(key)) return to_int(*n, field(key));
  return std::nullopt;
}

std::optional<bool> TableReader::optional_bool(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  auto b = n->as_boolean();
  if (!b) fail_type(*n, field(key), "true or false");
  return b->get();
}

std::string TableReader::required_string(std::string_view key, std::string_view what) const {
  const toml::node& n = require(key, what);
  auto s = n.as_string();
  if (!s) fail_type(n, field(key), what);
  return s->get();
}

std::optional<std::string> TableReader::optional_string(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  auto s = n->as_string();
  if (!s) fail_type(*n, field(key), "a string");
  return s->get();
}

std::vector<double> TableReader::number_list(std::string_view key, std::string_view what) const {
  const toml::node& n = require(key, what);
  auto a = n.as_array();
  if (!a) fail_type(n, field(key), what);
  std::vector<double> out;
  out.reserve(a->size());
  for (std::size_t i = 0; i < a->size(); ++i)
    out.push_back(to_number(*a->get(i), fmt::format("{}[{}]", field(key), i)));
  return out;
}

std::vector<int> TableReader::int_list(std::string_view key, std::string_view what) const {
  const toml::node& n = require(key, what);
  auto a = n.as_array();
  if (!a) fail_type(n, field(key), what);
  std::vector<int> out;
  out.reserve(a->size());
  for (std::size_t i = 0; i < a->size(); ++i)
    out.push_back(to_int(*a->get(i), fmt::format("{}[{}]", field(key), i)));
  return out;
}

const toml::table* TableReader::optional_table(std::string_view key) const {
  const toml::node* n = node(key);
  if (n == nullptr) return nullptr;
  auto t = n->as_table();
  if (!t) fail_type(*n, field(key), fmt::format("a table [{}]", field(key)));
  return t;
}

const toml::array* TableReader::optional_table_array(std::string_view key, std::size_t max_tables) const {
  const toml::node* n = node(key);
  if (n == nullptr) return nullptr;
  auto a = n->as_array();
  if (!a || !a->is_array_of_tables())
    fail_type(*n, field(key), fmt::format("a list of tables [[{}]]", field(key)));
  if (a->size() > max_tables)
    fail(key, fmt::format("{} has {} tables; expected at most {} [[{}]] tables (docs/case-format.md, \"Size "
                          "limits\")",
                          field(key), a->size(), max_tables, field(key)));
  return a;
}

void TableReader::fail_value(std::string_view key, std::string_view expectation) const {
  const toml::node* n = node(key);
  throw InvalidInput(located(origin_, n != nullptr ? n : &table_,
                             fmt::format("{} = {}; expected {}", field(key),
                                         n != nullptr ? describe(*n) : "(absent)", expectation)));
}

void TableReader::fail_entry(std::string_view key, std::size_t index,
                             std::string_view expectation) const {
  const toml::node* n = node(key);
  const toml::node* entry = (n != nullptr && n->as_array()) ? n->as_array()->get(index) : nullptr;
  throw InvalidInput(
      located(origin_, entry != nullptr ? entry : &table_,
              fmt::format("{}[{}] = {}; expected {}", field(key), index,
                          entry != nullptr ? describe(*entry) : "(absent)", expectation)));
}

void TableReader::fail_missing(std::string_view key, std::string_view what) const {
  // The root table's position is the start of the file, which says nothing; omit it there.
  throw InvalidInput(located(origin_, path_.empty() ? nullptr : &table_,
                             fmt::format("{} is missing; expected {}", field(key), what)));
}

void TableReader::fail(std::string_view key, std::string_view message) const {
  const toml::node* n = node(key);
  throw InvalidInput(located(origin_, n != nullptr ? n : &table_, message));
}

}  // namespace frictopt::io::detail
