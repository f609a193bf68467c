// SPDX-License-Identifier: MIT
// study::load_change_warnings: a design that lowers Θ by carrying less load is named (the pad of
// a displacement-pressed Gmsh body went from 11.24 kN to 6.56 kN while its "uniform pressure"
// cost fell 65 %), a kept load is not, and the tangential load is compared with P⁰.
#include <gtest/gtest.h>

#include <string>

#include "frictopt/core/error.hpp"
#include "frictopt/study/load_change.hpp"

namespace {

using frictopt::contact::ContactResultants;
using frictopt::study::load_change_warnings;

ContactResultants load(double normal, double t1 = 0.0, double t2 = 0.0, double area = 1e-4, int dim = 3) {
  ContactResultants r;
  r.dim = dim;
  r.normal_force = normal;
  r.tangential_force = Eigen::Vector2d(t1, t2);
  r.tangential_force_norm = r.tangential_force.norm();
  r.contact_area = area;
  return r;
}

TEST(LoadChange, ADesignThatCarriesLessLoadIsNamedWithBothForces) {
  const auto w = load_change_warnings(load(11240.0, 0, 0, 3.1e-4), load(6560.0, 0, 0, 2.2e-4));
  ASSERT_EQ(w.size(), 1U);
  EXPECT_NE(w[0].find("total normal force 6560 N (initial 1.124e+04 N, -41.6 %; warned beyond ±10 %)"),
            std::string::npos)
      << w[0];
  EXPECT_NE(w[0].find("contact area 0.00022 m² (initial 0.00031 m²)"), std::string::npos) << w[0];
}

TEST(LoadChange, AKeptLoadGivesNoWarningAndTheBoundIsTheFraction) {
  EXPECT_TRUE(load_change_warnings(load(100.0), load(109.0)).empty());
  EXPECT_TRUE(load_change_warnings(load(100.0), load(91.0)).empty());
  EXPECT_EQ(load_change_warnings(load(100.0), load(111.0)).size(), 1U);
  EXPECT_EQ(load_change_warnings(load(100.0), load(104.0), 0.03).size(), 1U);
  EXPECT_TRUE(load_change_warnings(load(100.0), load(104.0), 0.05).empty());
}

TEST(LoadChange, LostContactIsOneWarning) {
  const auto w = load_change_warnings(load(5.0e4, 0, 0, 1e-3, 2), load(0.0, 0, 0, 0.0, 2));
  ASSERT_EQ(w.size(), 1U);
  EXPECT_NE(w[0].find("lost contact: total normal force 5e+04 N/m at the initial design"), std::string::npos) << w[0];
}

TEST(LoadChange, TheTangentialLoadIsComparedWithTheInitialNormalForce) {
  // P kept, T turned by 90° at the same magnitude: |ΔT| = √2·30 = 42.4 > 0.1·200.
  const auto w = load_change_warnings(load(200.0, 30.0, 0.0), load(200.0, 0.0, 30.0));
  ASSERT_EQ(w.size(), 1U);
  EXPECT_NE(w[0].find("different tangential load"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("21.2 % of the initial normal force"), std::string::npos) << w[0];
  EXPECT_TRUE(load_change_warnings(load(200.0, 30.0, 0.0), load(200.0, 45.0, 0.0)).empty());
}

TEST(LoadChange, NothingToCompareWithoutAnInitialLoad) {
  EXPECT_TRUE(load_change_warnings(load(0.0), load(10.0)).empty());
  EXPECT_THROW((void)load_change_warnings(load(1.0), load(2.0), 0.0), frictopt::InvalidInput);
  EXPECT_THROW((void)load_change_warnings(load(1.0), load(2.0), 1.5), frictopt::InvalidInput);
}

}  // namespace
