// SPDX-License-Identifier: MIT
// The shared validation helper: message layout and shortest round-trip numbers.
#include "frictopt/core/validation.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <limits>

#include "frictopt/core/error.hpp"

namespace {

TEST(Validation, FormatNumberRoundTripsAndNamesNonFiniteValues) {
  for (double x : {0.3, 1e-300, 1e308, -2.5, 0.1 + 0.2, 7e10}) {
    const std::string text = frictopt::format_number(x);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), x) << text;
  }
  EXPECT_EQ(frictopt::format_number(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(frictopt::format_number(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(Validation, FailFieldNamesContextFieldValueAndExpectation) {
  try {
    frictopt::require_field(false, "case.toml:3", "material.poisson", 0.6, "0 <= poisson <= 0.49");
    FAIL() << "no exception";
  } catch (const frictopt::InvalidInput& e) {
    EXPECT_STREQ(e.what(), "case.toml:3: material.poisson = 0.6; expected 0 <= poisson <= 0.49");
  }
  EXPECT_NO_THROW(frictopt::require_field(true, "", "x", 1.0, "anything"));
  EXPECT_THROW(frictopt::fail_field("", "x", "1", "2"), frictopt::InvalidInput);
}

}  // namespace
