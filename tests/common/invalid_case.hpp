// SPDX-License-Identifier: MIT
// Test helpers for the case parser's error messages (shared by the io tests).
#pragma once

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <string_view>

#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"

namespace frictopt::testing {

/// `base` with the first occurrence of `from` replaced by `to`; fails the test if absent, so
/// a mutation cannot silently test the unmodified case.
inline std::string replaced(std::string_view base, std::string_view from, std::string_view to) {
  std::string text(base);
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "'" << from << "' not in the base case";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// Expects io::parse_case(text, "case.toml") to throw InvalidInput whose message starts with the
/// file name and contains every fragment and none of `absent`.
inline void expect_invalid_case(const std::string& text, std::initializer_list<std::string_view> fragments,
                                std::initializer_list<std::string_view> absent = {}) {
  try {
    (void)io::parse_case(text, "case.toml");
    ADD_FAILURE() << "no InvalidInput; expected a message with '" << *fragments.begin() << "'";
  } catch (const InvalidInput& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("case.toml", 0), 0u) << message;
    for (std::string_view f : fragments) EXPECT_NE(message.find(f), std::string::npos) << "'" << f << "' not in: " << message;
    for (std::string_view a : absent) EXPECT_EQ(message.find(a), std::string::npos) << "'" << a << "' in: " << message;
  }
}

}  // namespace frictopt::testing
