// SPDX-License-Identifier: MIT
#include "frictopt/core/error.hpp"

#include <cstdio>
#include <cstdlib>

namespace frictopt::detail {

void assert_failed(const char* condition, const std::string& message,
                   const std::source_location& where) {
  // The one place the library prints: a failed assert is a bug, reported and fatal.
  std::fprintf(stderr, "assert failed: %s (%s) at %s:%u\n", condition, message.c_str(),
               where.file_name(), static_cast<unsigned>(where.line()));
  std::abort();
}

}  // namespace frictopt::detail
