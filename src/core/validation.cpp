// SPDX-License-Identifier: MIT
#include "frictopt/core/validation.hpp"

#include <charconv>
#include <cmath>

#include "frictopt/core/error.hpp"

namespace frictopt {

std::string format_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];
  // std::to_chars without a precision is the shortest round-trip form.
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return ec == std::errc() ? std::string(buffer, end) : std::to_string(value);
}

void fail_field(std::string_view context, std::string_view field, std::string_view value,
                std::string_view expectation) {
  std::string message;
  if (!context.empty()) message.append(context).append(": ");
  message.append(field).append(" = ").append(value).append("; expected ").append(expectation);
  throw InvalidInput(message);
}

}  // namespace frictopt
