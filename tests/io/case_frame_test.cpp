// SPDX-License-Identifier: MIT
// The case keys of the contact frame: [contact.friction] orientation_deg (a law turned in the
// foundation's tangent plane) — parsed values and the exit-2 messages naming the key.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "common/invalid_case.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/io/case_file.hpp"

namespace frictopt::io {
namespace {

using testing::expect_invalid_case;
using testing::replaced;

std::string read_case(const char* name) {
  std::ifstream in(std::string(FRICTOPT_SOURCE_DIR) + "/tests/io/data/" + name);
  std::ostringstream text;
  text << in.rdbuf();
  EXPECT_FALSE(text.str().empty()) << name;
  return text.str();
}

TEST(CaseFrictionOrientation, TurnsEvery3dLawByTheGivenDegrees) {
  const std::string base = read_case("fclib3d.toml");
  const std::string disc = "kind = \"disc_exact\"\nmu = 0.3";
  for (const std::string law : {"kind = \"disc_exact\"\nmu = 0.3", "kind = \"isotropic\"\nmu = 0.3\nn = 8",
                                "kind = \"polygon\"\nmu_vertices = [0.3, 0.2, 0.3, 0.2]",
                                "kind = \"ellipse\"\nmu_x = 0.4\nmu_y = 0.2", "kind = \"ellipse_exact\"\nmu_x = 0.4\nmu_y = 0.2"}) {
    const contact::FrictionLaw plain = parse_case(replaced(base, disc, law), "case.toml").body.contact->law;
    const contact::FrictionLaw turned =
        parse_case(replaced(base, disc, law + "\norientation_deg = 30.0"), "case.toml").body.contact->law;
    SCOPED_TRACE(turned.describe());
    EXPECT_EQ(plain.orientation(), 0.0);
    EXPECT_NEAR(turned.orientation(), std::numbers::pi / 6, 1e-15);
    EXPECT_NE(turned.describe().find("orientation_deg=30"), std::string::npos);
    const Eigen::Vector2d u(0.6, -0.8);
    const double c = std::cos(std::numbers::pi / 6), s = std::sin(std::numbers::pi / 6);
    EXPECT_NEAR(turned.support(Eigen::Vector2d(c * u.x() - s * u.y(), s * u.x() + c * u.y())), plain.support(u), 1e-15);
  }
}

TEST(CaseFrictionOrientation, RefusesANonzeroAngleIn2dAndAnAngleOutOfRange) {
  const std::string base2d = read_case("fclib2d.toml");
  const std::string iso = "kind = \"isotropic\"\nmu = 0.3";
  EXPECT_EQ(parse_case(replaced(base2d, iso, std::string(iso) + "\norientation_deg = 0.0"), "case.toml")
                .body.contact->law.orientation(),
            0.0);
  expect_invalid_case(replaced(base2d, iso, std::string(iso) + "\norientation_deg = 10.0"),
                      {"contact.friction.orientation_deg = 10", "0 in 2D"});
  const std::string base3d = read_case("fclib3d.toml");
  const std::string disc = "kind = \"disc_exact\"\nmu = 0.3";
  expect_invalid_case(replaced(base3d, disc, std::string(disc) + "\norientation_deg = 400.0"),
                      {"contact.friction.orientation_deg = 400", "−360 <= orientation_deg <= 360"});
  expect_invalid_case(replaced(base3d, disc, std::string(disc) + "\norientation_deg = \"east\""),
                      {"contact.friction.orientation_deg"});
  expect_invalid_case(replaced(base3d, disc, "kind = \"none\"\norientation_deg = 10.0"),
                      {"contact.friction.orientation_deg", "not used by kind = \"none\""});
}

// [foundation]: normal (normalized), offset, axis1; the defaults are the thesis' foundation.
TEST(CaseFoundation, ReadsNormalOffsetAndAxis) {
  const std::string base = read_case("fclib3d.toml");
  const contact::Foundation plain = parse_case(base, "case.toml").body.contact->foundation;
  EXPECT_TRUE(plain.is_standard(3));
  const contact::Foundation f =
      parse_case(base + "\n[foundation]\nnormal = [0.0, 0.0, 2.0]\noffset = -1.0e-3\naxis1 = [1.0, 1.0, 0.0]\n", "case.toml")
          .body.contact->foundation;
  EXPECT_EQ(f.offset, -1e-3);
  EXPECT_LE((f.frame.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
  EXPECT_LE((f.frame.tangents.col(0) - Eigen::Vector3d(1.0, 1.0, 0.0).normalized()).norm(), 1e-15);
  EXPECT_LE((f.frame.tangents.col(1) - Eigen::Vector3d(-1.0, 1.0, 0.0).normalized()).norm(), 1e-15);
  // Default axis1: e1 projected onto the plane.
  const contact::Foundation tilted =
      parse_case(base + "\n[foundation]\nnormal = [1.0, 0.0, 1.0]\n", "case.toml").body.contact->foundation;
  EXPECT_LE((tilted.frame.tangents.col(0) - Eigen::Vector3d(1.0, 0.0, -1.0).normalized()).norm(), 1e-15);
  EXPECT_FALSE(tilted.is_standard(3));
  // Explicitly standard: still the thesis' foundation.
  EXPECT_TRUE(parse_case(base + "\n[foundation]\nnormal = [0, 0, 1]\noffset = 0\n", "case.toml")
                  .body.contact->foundation.is_standard(3));
  const std::string base2d = read_case("fclib2d.toml");
  const contact::Foundation f2 =
      parse_case(base2d + "\n[foundation]\nnormal = [0.0, 1.0]\n", "case.toml").body.contact->foundation;
  EXPECT_TRUE(f2.is_standard(2));
}

TEST(CaseFoundation, RefusesABadNormalOrAxisNamingTheKey) {
  const std::string base = read_case("fclib3d.toml");
  expect_invalid_case(base + "\n[foundation]\nnormal = [0.0, 0.0, 0.0]\n", {"foundation.normal", "not all zero"});
  expect_invalid_case(base + "\n[foundation]\nnormal = [0.0, 1.0]\n", {"foundation.normal", "a list of 3 numbers"});
  expect_invalid_case(base + "\n[foundation]\nnormal = [0.0, 0.0, 1.0]\naxis1 = [0.0, 0.0, -3.0]\n",
                      {"foundation.axis1", "is parallel to foundation.normal"});
  expect_invalid_case(base + "\n[foundation]\naxis1 = [0.0, 0.0, 0.0]\n", {"foundation.axis1", "not all zero"});
  expect_invalid_case(base + "\n[foundation]\noffset = \"low\"\n", {"foundation.offset"});
  expect_invalid_case(base + "\n[foundation]\nnormale = [0.0, 0.0, 1.0]\n", {"normale"});
  const std::string base2d = read_case("fclib2d.toml");
  expect_invalid_case(base2d + "\n[foundation]\naxis1 = [1.0, 0.0, 0.0]\n", {"foundation.axis1", "expected no axis1 in 2D"});
  const std::size_t contact = base.find("[contact.friction]");
  ASSERT_NE(contact, std::string::npos);
  expect_invalid_case(base.substr(0, contact) + "[foundation]\nnormal = [0.0, 0.0, 1.0]\n",
                      {"[foundation] needs a [contact] table"});
}

}  // namespace
}  // namespace frictopt::io
