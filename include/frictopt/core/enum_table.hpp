// SPDX-License-Identifier: MIT
// One table per enum gives both directions (to_string and parse), so the spellings used by
// case files, reports and the CLI cannot drift.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "frictopt/core/error.hpp"

namespace frictopt::detail {

template <class Enum, std::size_t N>
struct EnumTable {
  std::array<std::pair<Enum, std::string_view>, N> entries;

  [[nodiscard]] constexpr std::string_view name(Enum value) const {
    for (const auto& [e, text] : entries)
      if (e == value) return text;
    return "?";
  }

  [[nodiscard]] constexpr std::optional<Enum> find(std::string_view text) const {
    for (const auto& [e, spelling] : entries)
      if (spelling == text) return e;
    return std::nullopt;
  }

  /// "a, b, c": the accepted spellings, for messages.
  [[nodiscard]] std::string spellings() const {
    std::string out;
    for (const auto& [e, text] : entries) {
      if (!out.empty()) out += ", ";
      out += text;
    }
    return out;
  }

  /// Parses `text`; throws InvalidInput "<what> = 'text'; expected one of ...".
  [[nodiscard]] Enum parse(std::string_view text, std::string_view what) const {
    if (auto e = find(text)) return *e;
    throw InvalidInput(std::string(what) + " = '" + std::string(text) + "'; expected one of " +
                       spellings());
  }
};

template <class Enum, class... Pairs>
constexpr auto make_enum_table(Pairs... pairs) {
  return EnumTable<Enum, sizeof...(Pairs)>{{std::pair<Enum, std::string_view>(pairs)...}};
}

}  // namespace frictopt::detail
