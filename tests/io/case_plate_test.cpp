// SPDX-License-Identifier: MIT
// [[plate]] tables (docs/case-format.md, "[[plate]]"): what they read into the body, and the
// refusals naming the file, the field and the expectation.
#include <gtest/gtest.h>

#include <string>

#include "common/case_text.hpp"
#include "common/invalid_case.hpp"
#include "frictopt/io/case_file.hpp"

namespace frictopt::io {
namespace {

using testing::block_header_3d;
using testing::design_table;
using testing::expect_invalid_case;
using testing::replaced;

const std::string kPlateCase = block_header_3d("0.1", "0.05") + design_table("[3, 3]", "1e-5", "1e-4") + R"(
[contact]
[contact.friction]
kind = "isotropic"
mu = 0.3

[[plate]]
face = "top"
force = [0.0, 0.0, -2.0e4]
held = ["x", "y"]
)";

TEST(CasePlate, ReadsFaceForceAndDirections) {
  const CaseDescription c = parse_case(kPlateCase, "case.toml");
  ASSERT_EQ(c.body.plates.size(), 1u);
  const fem::LoadingPlate& p = c.body.plates[0];
  EXPECT_EQ(p.boundary, "top");
  EXPECT_EQ(p.force(2), -2e4);
  EXPECT_EQ(p.held, (std::vector<int>{0, 1}));
  EXPECT_EQ(p.tied, (std::vector<int>{2}));  // default: every direction not held
  EXPECT_TRUE(c.body.dirichlet.empty());     // a plate with [contact] needs no [[dirichlet]]
  const CaseDescription all = parse_case(replaced(kPlateCase, "held = [\"x\", \"y\"]", "tied = [\"z\", \"x\"]"), "case.toml");
  EXPECT_EQ(all.body.plates[0].tied, (std::vector<int>{0, 2}));  // sorted; y neither held nor tied
  EXPECT_TRUE(all.body.plates[0].held.empty());
}

TEST(CasePlate, RefusesWhatCannotBeAPlate) {
  expect_invalid_case(replaced(kPlateCase, "face = \"top\"", "face = \"lid\""), {"plate[0].face", "left, right"});
  expect_invalid_case(replaced(kPlateCase, "face = \"top\"", "face = \"bottom\""), {"plate[0].face", "contact surface"});
  expect_invalid_case(replaced(kPlateCase, "face = \"top\"", "boundary = \"Top\""), {"plate[0].boundary", "structured box"});
  expect_invalid_case(replaced(kPlateCase, "[0.0, 0.0, -2.0e4]", "[0.0, -2.0e4]"), {"plate[0].force", "3 finite numbers"});
  expect_invalid_case(replaced(kPlateCase, "[0.0, 0.0, -2.0e4]", "[1.0, 0.0, -2.0e4]"),
                      {"plate[0].force[0] = 1 N", "holds at zero displacement"});
  expect_invalid_case(replaced(kPlateCase, "held = [\"x\", \"y\"]", "held = [\"x\", \"y\"]\ntied = [\"z\", \"x\"]"),
                      {"direction \"x\" is both held and tied"});
  expect_invalid_case(replaced(kPlateCase, "held = [\"x\", \"y\"]", "held = [\"x\", \"w\"]"), {"plate[0].held[1]", "\"z\""});
  expect_invalid_case(replaced(kPlateCase, "held = [\"x\", \"y\"]", "held = [\"x\", \"x\"]"), {"plate[0].held[1]", "not already listed"});
  expect_invalid_case(replaced(kPlateCase, "held = [\"x\", \"y\"]", "helt = [\"x\", \"y\"]"), {"plate[0]", "helt", "held"});
  expect_invalid_case(replaced(kPlateCase, "[contact]",
                               "[[dirichlet]]\nface = \"top\"\ncomponents = [0]\n[contact]"),
                      {"plate[0]", "\"top\" is fixed in direction \"x\" by dirichlet[0]"});
  expect_invalid_case(kPlateCase + "[[plate]]\nface = \"top\"\nforce = [0.0, 0.0, 1.0]\n",
                      {"plate[1]", "already the part of plate[0]"});
}

TEST(CasePlate, TwoDimensionalPlatesHaveTwoComponents) {
  const std::string two_d = R"(
[geometry]
dim = 2
a = 2.0
height = 1.0
[mesh]
cells = [10, 4]
[material]
young = 2.1e11
poisson = 0.3
[design]
control_points = [5]
initial = 0.05
upper_bound = 0.75
[contact]
[contact.friction]
kind = "isotropic"
mu = 0.3
[[plate]]
face = "top"
force = [0.0, -1.0e6]
held = ["x"]
)";
  EXPECT_EQ(parse_case(two_d, "case.toml").body.plates[0].tied, (std::vector<int>{1}));
  expect_invalid_case(replaced(two_d, "[0.0, -1.0e6]", "[0.0, 0.0, -1.0e6]"), {"plate[0].force", "2 finite numbers"});
  expect_invalid_case(replaced(two_d, "held = [\"x\"]", "held = [\"z\"]"), {"plate[0].held[0]", "2D body"});
  expect_invalid_case(replaced(two_d, "face = \"top\"", "face = \"front\""), {"plate[0].face"});
}

}  // namespace
}  // namespace frictopt::io
