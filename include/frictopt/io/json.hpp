// SPDX-License-Identifier: MIT
// A small JSON value type for summaries, reports and certificates, and its writer.
//
// Why an own type rather than nlohmann::json in the interface: the JSON library then stays a
// private dependency of io (like TOML and VTK), modules building reports need not compile
// nlohmann's large header, and the value keeps object keys in insertion order, so a
// summary's fields appear in the order the code lists them (readable, diff-friendly). The
// (de)serialisation itself is nlohmann's, in src/io/json.cpp.
#pragma once

#include <Eigen/Core>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace frictopt::io {

class JsonValue {
 public:
  using Array = std::vector<JsonValue>;
  /// Key-value pairs in insertion order; keys are unique (operator[] finds before adding).
  using Object = std::vector<std::pair<std::string, JsonValue>>;

  JsonValue() = default;  ///< null
  JsonValue(std::nullptr_t) {}
  JsonValue(bool b) : value_(b) {}
  template <std::integral T>
  requires(!std::same_as<T, bool>) JsonValue(T i) : value_(static_cast<std::int64_t>(i)) {}
  template <std::floating_point T>
  JsonValue(T x) : value_(static_cast<double>(x)) {}
  JsonValue(const char* s) : value_(std::string(s)) {}
  JsonValue(std::string s) : value_(std::move(s)) {}
  JsonValue(std::string_view s) : value_(std::string(s)) {}
  JsonValue(Array a) : value_(std::move(a)) {}
  JsonValue(Object o) : value_(std::move(o)) {}
  /// An array of numbers (e.g. a design vector α). The VectorXd overload makes
  /// `json["alpha"] = alpha;` work (the Ref one alone would need two conversions).
  JsonValue(const Eigen::VectorXd& v);
  JsonValue(const Eigen::Ref<const Eigen::VectorXd>& v);
  JsonValue(std::span<const double> v);

  [[nodiscard]] static JsonValue array() { return JsonValue(Array{}); }
  [[nodiscard]] static JsonValue object() { return JsonValue(Object{}); }

  [[nodiscard]] bool is_null() const { return std::holds_alternative<std::nullptr_t>(value_); }
  [[nodiscard]] bool is_bool() const { return std::holds_alternative<bool>(value_); }
  [[nodiscard]] bool is_integer() const { return std::holds_alternative<std::int64_t>(value_); }
  [[nodiscard]] bool is_real() const { return std::holds_alternative<double>(value_); }
  [[nodiscard]] bool is_string() const { return std::holds_alternative<std::string>(value_); }
  [[nodiscard]] bool is_array() const { return std::holds_alternative<Array>(value_); }
  [[nodiscard]] bool is_object() const { return std::holds_alternative<Object>(value_); }

  /// Typed access; each throws InvalidInput if the value holds another type.
  [[nodiscard]] bool as_bool() const;
  [[nodiscard]] std::int64_t as_integer() const;
  /// An integer or a real, as double.
  [[nodiscard]] double as_number() const;
  [[nodiscard]] const std::string& as_string() const;
  [[nodiscard]] const Array& as_array() const;
  [[nodiscard]] const Object& as_object() const;

  /// Object member `key`, added as null if absent; a null value becomes an empty object
  /// first. Throws InvalidInput on other types.
  JsonValue& operator[](std::string_view key);
  /// Object member `key`; throws InvalidInput if absent or not an object.
  [[nodiscard]] const JsonValue& at(std::string_view key) const;
  [[nodiscard]] bool contains(std::string_view key) const;
  /// Appends to an array; a null value becomes an empty array first.
  void push_back(JsonValue value);

  friend bool operator==(const JsonValue&, const JsonValue&) = default;

 private:
  std::variant<std::nullptr_t, bool, std::int64_t, double, std::string, Array, Object> value_;
};

/// The JSON text of `value`, indented by `indent` spaces per level (negative: one line).
/// Reals are written so they read back exactly; NaN and infinities, which JSON lacks, become
/// null (a Summary's "not computed" NaN reads as null). Throws InvalidInput on a string that
/// is not valid UTF-8.
[[nodiscard]] std::string to_json_string(const JsonValue& value, int indent = 2);

/// Parses JSON text. Throws InvalidInput with the position of a syntax error.
/// Arrays and objects may nest at most kMaxJsonDepth deep (frictopt's own files nest a few
/// levels): a deeper text is refused before it is parsed, so no recursion can exhaust the stack.
[[nodiscard]] JsonValue parse_json(std::string_view text);
inline constexpr int kMaxJsonDepth = 64;

/// Reads and parses the JSON file `path` (a regular file of at most `max_bytes`; a FIFO or
/// device is refused without waiting). Every error names the file and `what` ("the design
/// file"): InvalidInput for a missing, non-regular, oversized or malformed file,
/// FileSystemError when the system refuses to read it.
[[nodiscard]] JsonValue read_json_file(const std::filesystem::path& path, std::string_view what,
                                       std::size_t max_bytes = std::size_t{1} << 30);

/// Writes to_json_string(value) plus a newline to `path`, atomically (temporary file +
/// rename). Throws FileSystemError (exit 5) if the file cannot be written; the previous file
/// is then kept.
void write_json(const std::filesystem::path& path, const JsonValue& value, int indent = 2);

}  // namespace frictopt::io
