// SPDX-License-Identifier: MIT
// contact_resultants: totals, areas, counts and the stick zone of hand-built states whose
// answers are known by hand.
#include "frictopt/contact/contact_resultants.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "frictopt/core/error.hpp"

namespace frictopt::contact {
namespace {

// Four 3D nodes: z_i = (q_i, λ_i), statuses set by hand (the resultants read the classification).
ContactState four_nodes() {
  ContactState s(3, 4);
  s.z << 1.0, 2.0, 10.0,  // stick
      -0.5, 0.0, 5.0,     // stick
      3.0, 0.0, 10.0,     // slip
      0.0, 0.0, 0.0;      // separated
  s.nodes.resize(4);
  s.nodes[0].status = s.nodes[1].status = NodeStatus::kStick;
  s.nodes[2].status = NodeStatus::kSlip;
  s.nodes[3].status = NodeStatus::kSeparated;
  return s;
}

TEST(ContactResultants, TotalsAreasAndStickZoneOf3dState) {
  const ContactState s = four_nodes();
  const Eigen::Vector4d areas(1.0, 3.0, 2.0, 4.0);
  Eigen::MatrixXd plane(4, 2);
  plane << 0.0, 0.0, 4.0, 8.0, 1.0, 1.0, 9.0, 9.0;
  const ContactResultants r = contact_resultants(s, areas, plane);
  EXPECT_DOUBLE_EQ(r.normal_force, 25.0);
  // τ = −Σ q = −(3.5, 2.0)
  EXPECT_DOUBLE_EQ(r.tangential_force(0), -3.5);
  EXPECT_DOUBLE_EQ(r.tangential_force(1), -2.0);
  EXPECT_DOUBLE_EQ(r.tangential_force_norm, std::hypot(3.5, 2.0));
  EXPECT_DOUBLE_EQ(r.force_ratio, std::hypot(3.5, 2.0) / 25.0);
  EXPECT_EQ(r.num_stick, 2);
  EXPECT_EQ(r.num_slip, 1);
  EXPECT_EQ(r.num_separated, 1);
  EXPECT_DOUBLE_EQ(r.stick_area, 4.0);
  EXPECT_DOUBLE_EQ(r.slip_area, 2.0);
  EXPECT_DOUBLE_EQ(r.separated_area, 4.0);
  EXPECT_DOUBLE_EQ(r.contact_area, 6.0);
  // Area-weighted centroid of (0,0)·1 and (4,8)·3 over 4.
  EXPECT_DOUBLE_EQ(r.stick_centroid(0), 3.0);
  EXPECT_DOUBLE_EQ(r.stick_centroid(1), 6.0);
  EXPECT_DOUBLE_EQ(r.stick_equivalent_radius, std::sqrt(4.0 / std::numbers::pi));
  EXPECT_DOUBLE_EQ(r.contact_equivalent_radius, std::sqrt(6.0 / std::numbers::pi));
  EXPECT_NE(r.brief_report().find("stick 2"), std::string::npos);
}

TEST(ContactResultants, TwoDimensionalHalfWidthAndNoStickZone) {
  ContactState s(2, 3);
  s.z << 0.2, 1.0, -0.3, 1.0, 0.0, 0.0;
  s.nodes.resize(3);
  s.nodes[0].status = s.nodes[1].status = NodeStatus::kSlip;
  s.nodes[2].status = NodeStatus::kSeparated;
  const Eigen::Vector3d areas(0.5, 1.0, 0.5);
  const Eigen::MatrixXd plane = Eigen::Vector3d(0.0, 1.0, 2.0);
  const ContactResultants r = contact_resultants(s, areas, plane);
  EXPECT_DOUBLE_EQ(r.normal_force, 2.0);
  EXPECT_DOUBLE_EQ(r.tangential_force(0), 0.1);
  EXPECT_DOUBLE_EQ(r.tangential_force(1), 0.0);
  EXPECT_DOUBLE_EQ(r.force_ratio, 0.05);
  EXPECT_EQ(r.num_stick, 0);
  EXPECT_TRUE(std::isnan(r.stick_centroid(0)));
  EXPECT_DOUBLE_EQ(r.stick_equivalent_radius, 0.0);
  EXPECT_DOUBLE_EQ(r.contact_equivalent_radius, 0.75);  // half of the 1.5 m contact length
}

TEST(ContactResultants, NoNormalForceGivesNaNRatio) {
  ContactState s(3, 1);
  s.nodes.resize(1);
  const ContactResultants r =
      contact_resultants(s, Eigen::VectorXd::Ones(1), Eigen::MatrixXd::Zero(1, 2));
  EXPECT_TRUE(std::isnan(r.force_ratio));
  EXPECT_EQ(r.num_separated, 1);
}

TEST(ContactResultants, SizeMismatchIsInvalidInput) {
  const ContactState s = four_nodes();
  EXPECT_THROW((void)contact_resultants(s, Eigen::VectorXd::Ones(3), Eigen::MatrixXd::Zero(4, 2)),
               InvalidInput);
  EXPECT_THROW((void)contact_resultants(s, Eigen::VectorXd::Ones(4), Eigen::MatrixXd::Zero(4, 1)),
               InvalidInput);
}

}  // namespace
}  // namespace frictopt::contact
