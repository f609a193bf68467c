// SPDX-License-Identifier: MIT
#include "frictopt/io/json.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "atomic_file.hpp"
#include "input_file.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::io {
namespace {

// nlohmann's ordered_json keeps insertion order, matching JsonValue::Object.
using Json = nlohmann::ordered_json;

Json to_nlohmann(const JsonValue& v) {
  if (v.is_null()) return nullptr;
  if (v.is_bool()) return v.as_bool();
  if (v.is_integer()) return v.as_integer();
  if (v.is_real()) {
    const double x = v.as_number();
    return std::isfinite(x) ? Json(x) : Json(nullptr);
  }
  if (v.is_string()) return v.as_string();
  if (v.is_array()) {
    Json out = Json::array();
    for (const JsonValue& e : v.as_array()) out.push_back(to_nlohmann(e));
    return out;
  }
  Json out = Json::object();
  for (const auto& [key, e] : v.as_object()) out[key] = to_nlohmann(e);
  return out;
}

JsonValue from_nlohmann(const Json& j) {
  switch (j.type()) {
    case Json::value_t::null:
      return JsonValue();
    case Json::value_t::boolean:
      return JsonValue(j.get<bool>());
    case Json::value_t::number_integer:
      return JsonValue(j.get<std::int64_t>());
    case Json::value_t::number_unsigned: {
      const auto u = j.get<std::uint64_t>();
      if (u > static_cast<std::uint64_t>(INT64_MAX)) return JsonValue(static_cast<double>(u));
      return JsonValue(static_cast<std::int64_t>(u));
    }
    case Json::value_t::number_float:
      return JsonValue(j.get<double>());
    case Json::value_t::string:
      return JsonValue(j.get<std::string>());
    case Json::value_t::array: {
      JsonValue::Array out;
      for (const Json& e : j) out.push_back(from_nlohmann(e));
      return JsonValue(std::move(out));
    }
    case Json::value_t::object: {
      JsonValue::Object out;
      for (const auto& [key, e] : j.items()) out.emplace_back(key, from_nlohmann(e));
      return JsonValue(std::move(out));
    }
    default:
      throw InvalidInput("parse_json: binary values are not supported");
  }
}

[[noreturn]] void wrong_type(std::string_view expected) {
  throw InvalidInput(fmt::format("JsonValue: expected {}", expected));
}

}  // namespace

JsonValue::JsonValue(const Eigen::VectorXd& v)
    : JsonValue(std::span<const double>(v.data(), static_cast<std::size_t>(v.size()))) {}

JsonValue::JsonValue(const Eigen::Ref<const Eigen::VectorXd>& v)
    : JsonValue(std::span<const double>(v.data(), static_cast<std::size_t>(v.size()))) {}

JsonValue::JsonValue(std::span<const double> v) {
  Array a;
  a.reserve(v.size());
  for (double x : v) a.emplace_back(x);
  value_ = std::move(a);
}

bool JsonValue::as_bool() const {
  if (!is_bool()) wrong_type("a boolean");
  return std::get<bool>(value_);
}

std::int64_t JsonValue::as_integer() const {
  if (!is_integer()) wrong_type("an integer");
  return std::get<std::int64_t>(value_);
}

double JsonValue::as_number() const {
  if (is_integer()) return static_cast<double>(std::get<std::int64_t>(value_));
  if (!is_real()) wrong_type("a number");
  return std::get<double>(value_);
}

const std::string& JsonValue::as_string() const {
  if (!is_string()) wrong_type("a string");
  return std::get<std::string>(value_);
}

const JsonValue::Array& JsonValue::as_array() const {
  if (!is_array()) wrong_type("an array");
  return std::get<Array>(value_);
}

const JsonValue::Object& JsonValue::as_object() const {
  if (!is_object()) wrong_type("an object");
  return std::get<Object>(value_);
}

JsonValue& JsonValue::operator[](std::string_view key) {
  if (is_null()) value_ = Object{};
  if (!is_object()) wrong_type("an object (to index by key)");
  Object& members = std::get<Object>(value_);
  for (auto& [k, v] : members)
    if (k == key) return v;
  members.emplace_back(std::string(key), JsonValue());
  return members.back().second;
}

const JsonValue& JsonValue::at(std::string_view key) const {
  for (const auto& [k, v] : as_object())
    if (k == key) return v;
  throw InvalidInput(fmt::format("JsonValue: no member '{}'", key));
}

bool JsonValue::contains(std::string_view key) const {
  if (!is_object()) return false;
  const Object& members = std::get<Object>(value_);
  return std::any_of(members.begin(), members.end(),
                     [&](const auto& member) { return member.first == key; });
}

void JsonValue::push_back(JsonValue value) {
  if (is_null()) value_ = Array{};
  if (!is_array()) wrong_type("an array (to append)");
  std::get<Array>(value_).push_back(std::move(value));
}

std::string to_json_string(const JsonValue& value, int indent) {
  try {
    // nlohmann prints doubles with max_digits10 precision, so they read back exactly.
    return to_nlohmann(value).dump(indent);
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInput(fmt::format("to_json_string: {}", e.what()));
  }
}

namespace {

// The deepest nesting of arrays and objects in `text`, counted outside strings, stopping as
// soon as it exceeds `limit`.
int nesting_depth(std::string_view text, int limit) {
  int depth = 0;
  int deepest = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (in_string) {
      if (ch == '\\') ++i;  // the escaped character cannot end the string
      else if (ch == '"') in_string = false;
      continue;
    }
    if (ch == '"') {
      in_string = true;
    } else if (ch == '[' || ch == '{') {
      deepest = std::max(deepest, ++depth);
      if (deepest > limit) return deepest;
    } else if (ch == ']' || ch == '}') {
      --depth;
    }
  }
  return deepest;
}

}  // namespace

JsonValue parse_json(std::string_view text) {
  if (nesting_depth(text, kMaxJsonDepth) > kMaxJsonDepth)
    throw InvalidInput(fmt::format("parse_json: arrays and objects nested deeper than {} levels; expected a "
                                   "file of frictopt's (a few levels)",
                                   kMaxJsonDepth));
  try {
    return from_nlohmann(Json::parse(text));
  } catch (const nlohmann::json::parse_error& e) {
    throw InvalidInput(fmt::format("parse_json: {}", e.what()));
  }
}

JsonValue read_json_file(const std::filesystem::path& path, std::string_view what, std::size_t max_bytes) {
  const std::string text = detail::read_input_file(path, what, max_bytes);
  try {
    return parse_json(text);
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("{}: {} is not valid JSON ({})", path.string(), what, e.what()));
  }
}

void write_json(const std::filesystem::path& path, const JsonValue& value, int indent) {
  detail::write_file_atomically(path, to_json_string(value, indent) + "\n");
}

}  // namespace frictopt::io
