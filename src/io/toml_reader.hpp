// SPDX-License-Identifier: MIT
// A strict reader over one TOML table: it rejects unknown keys on construction, reads typed
// values (an integer is a valid number, a float is not a valid integer), and builds the
// InvalidInput messages "origin:line: field = value; expected ...". The case parser uses
// one TableReader per case-file table, so adding a table is adding one function.
#pragma once

#include <toml++/toml.h>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace frictopt::io::detail {

/// The most tables of one [[kind]] of the body ([[load]], [[dirichlet]], [[force]],
/// [[constraint]]; docs/case-format.md, "Size limits"): each is applied node by node, and every
/// program step and load case carries one scale per table.
inline constexpr std::size_t kMaxBodyTables = 1'000;

/// "origin:line: message" (or "origin: message" when `node` is null or has no position).
[[nodiscard]] std::string located(std::string_view origin, const toml::node* node,
                                  std::string_view message);

/// A short rendering of a TOML value for messages: 0.6, "text", true, [1, 2], a table.
[[nodiscard]] std::string describe(const toml::node& node);

/// The key among `candidates` closest to `key` by edit distance, if it is close enough to be
/// a plausible typo (distance <= 2 and less than the key's length); else empty.
[[nodiscard]] std::string_view closest_key(std::string_view key,
                                           std::initializer_list<std::string_view> candidates);

class TableReader {
 public:
  /// Borrows `table` (must outlive the reader). `path` is the table's dotted name ("" for the
  /// root, "geometry", "load[1]"). Throws InvalidInput on the first key not in `allowed`.
  TableReader(const toml::table& table, std::string path, std::string_view origin,
              std::initializer_list<std::string_view> allowed);

  [[nodiscard]] bool has(std::string_view key) const;
  [[nodiscard]] const toml::node* node(std::string_view key) const;
  [[nodiscard]] const toml::table& table() const { return table_; }
  /// "path.key", or "key" at the root.
  [[nodiscard]] std::string field(std::string_view key) const;
  [[nodiscard]] const std::string& path() const { return path_; }

  // Typed access. required_* throws if the key is missing ("field is missing; expected
  // <what>"); every accessor throws if the value has the wrong type.
  [[nodiscard]] double required_number(std::string_view key, std::string_view what) const;
  [[nodiscard]] std::optional<double> optional_number(std::string_view key) const;
  [[nodiscard]] int required_int(std::string_view key, std::string_view what) const;
  [[nodiscard]] std::optional<int> optional_int(std::string_view key) const;
  [[nodiscard]] std::optional<bool> optional_bool(std::string_view key) const;
  [[nodiscard]] std::string required_string(std::string_view key, std::string_view what) const;
  [[nodiscard]] std::optional<std::string> optional_string(std::string_view key) const;
  /// A list of numbers (integers allowed); `what` describes the expected list.
  [[nodiscard]] std::vector<double> number_list(std::string_view key, std::string_view what) const;
  [[nodiscard]] std::vector<int> int_list(std::string_view key, std::string_view what) const;
  /// The sub-table at `key`, or null when absent; throws if `key` holds no table.
  [[nodiscard]] const toml::table* optional_table(std::string_view key) const;
  /// The array of tables at `key` ([[key]]), or null when absent; throws when it holds more than
  /// `max_tables` tables (a size limit of docs/case-format.md, "Size limits").
  [[nodiscard]] const toml::array* optional_table_array(std::string_view key, std::size_t max_tables) const;

  /// Throws "origin:line: field = value; expected <expectation>" for the value at `key`.
  [[noreturn]] void fail_value(std::string_view key, std::string_view expectation) const;
  /// As fail_value, for entry `index` of the list at `key` ("field[index] = v; ...").
  [[noreturn]] void fail_entry(std::string_view key, std::size_t index,
                               std::string_view expectation) const;
  /// Throws "origin:line: field is missing; expected <what>", at the table's line.
  [[noreturn]] void fail_missing(std::string_view key, std::string_view what) const;
  /// Throws "origin:line: <message>", at the line of `key` (or the table when absent).
  [[noreturn]] void fail(std::string_view key, std::string_view message) const;

 private:
  [[nodiscard]] const toml::node& require(std::string_view key, std::string_view what) const;
  [[nodiscard]] double to_number(const toml::node& n, std::string_view field_name) const;
  [[nodiscard]] int to_int(const toml::node& n, std::string_view field_name) const;
  [[noreturn]] void fail_type(const toml::node& n, std::string_view field_name,
                              std::string_view expected_type) const;

  const toml::table& table_;
  std::string path_;
  std::string origin_;
};

}  // namespace frictopt::io::detail
