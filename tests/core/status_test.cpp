// SPDX-License-Identifier: MIT
#include "frictopt/core/status.hpp"

#include <gtest/gtest.h>

#include "frictopt/core/error.hpp"

namespace frictopt {
namespace {

TEST(Status, SpellingsRoundTrip) {
  for (Status s : {Status::kNotRun, Status::kConverged, Status::kMaxIterations, Status::kStalled,
                   Status::kDiverged, Status::kNumericalFailure, Status::kStoppedByCallback})
    EXPECT_EQ(parse_status(to_string(s)), s);
}

TEST(Status, UnknownSpellingNamesTheAcceptedOnes) {
  try {
    (void)parse_status("done");
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("converged"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace frictopt
