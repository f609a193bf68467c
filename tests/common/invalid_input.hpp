// SPDX-License-Identifier: MIT
// The message of an expected InvalidInput, for tests that check what a message names.
#pragma once

#include <string>

#include "frictopt/core/error.hpp"

namespace frictopt::testing {

/// The message of the InvalidInput that f throws ("" when it throws none).
template <class F>
std::string invalid_input_message(F&& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

}  // namespace frictopt::testing
