// SPDX-License-Identifier: MIT
// The one way a frictopt module reports a bad value (Options::validate and the
// case parser): "<context>: <field> = <value>; expected <expectation>". Modules used to carry
// local num/fail/require copies of these; new code uses this header.
#pragma once

#include <string>
#include <string_view>

namespace frictopt {

/// The shortest decimal text that reads back as `value` ("0.3", "1e-300", "nan", "inf").
[[nodiscard]] std::string format_number(double value);

/// Throws InvalidInput "<context>: <field> = <value>; expected <expectation>" ("<field> = ..."
/// when `context` is empty).
[[noreturn]] void fail_field(std::string_view context, std::string_view field, std::string_view value,
                             std::string_view expectation);

/// fail_field(context, field, format_number(value), expectation) unless `ok`.
inline void require_field(bool ok, std::string_view context, std::string_view field, double value,
                          std::string_view expectation) {
  if (!ok) fail_field(context, field, format_number(value), expectation);
}

}  // namespace frictopt
