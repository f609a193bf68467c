// SPDX-License-Identifier: MIT
// The force-driven tribometer (TribometerDrive::kForce; docs/experiments.md, "Pulling with a
// force"): a floating block pressed by P and pulled by a ramped tangential force Q e_θ on its top
// face has a static equilibrium exactly while Q <= μ(θ)·P, μ(θ) the radial function of the friction
// set W in the force direction. The test asks the floating-body solver to FIND the equilibria up to
// the capacity (the a priori capacity report only rejects loads beyond it): the bisection's limit
// equilibrium must lie within 1e-3 relative of μ(θ)·P for every law — the resolution the
// augmented Lagrangian reaches where the dual is flat (measured 4e-8 to 6e-4, polygons best;
// docs/experiments.md §4) — its friction force must point along θ and the stick zone must shrink
// along the ramp. The law itself is validated to 1e-6 by the displacement drive
// (tribometer_test.cpp), which reaches steady sliding.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "frictopt/core/error.hpp"
#include "frictopt/study/tribometer.hpp"
#include "study/tribometer_specimen.hpp"

namespace frictopt::study {
namespace {

using contact::FrictionLaw;

BodyDefinition floating_specimen(const FrictionLaw& law) { return testing::tribometer_specimen(law); }

struct LawCase {
  std::string name;
  FrictionLaw law;
  std::vector<double> angles;
};

TEST(TribometerForceDrive, OnsetForceIsTheLawsCapacityForEveryLaw) {
  const std::vector<LawCase> cases = {
      {"disc 0.3", FrictionLaw::disc(0.3), {70.0}},
      {"16-gon 0.3", FrictionLaw::regular_polygon(0.3, 16), {100.0}},
      {"4-gon (0.4, 0.2, 0.4, 0.2)", FrictionLaw::polygon({0.4, 0.2, 0.4, 0.2}), {90.0}},
      {"ellipse 8-gon (0.4, 0.2)", FrictionLaw::ellipse_polygon(0.4, 0.2, 8), {10.0}},
      {"exact ellipse (0.4, 0.2)", FrictionLaw::ellipse(0.4, 0.2), {30.0}},
  };
  TribometerDefinition e;
  e.drive = TribometerDrive::kForce;
  e.normal_force = 1e4;
  e.max_force_ratio = 0.47;  // above every law's largest coefficient; no ramp point at a capacity
  e.ramp_steps = 10;
  e.onset_tolerance = 1e-5;
  std::printf("| law | θ [°] | onset Q [N] | μ(θ)·P [N] | rel. error | force φ [°] | slip ŝ [°] | normality | stick fraction at 0.9 Q_onset |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (const LawCase& lc : cases) {
    e.angles_degrees = lc.angles;
    Tribometer tribometer(floating_specimen(lc.law), e);
    const Tribometer::Summary summary = tribometer.run();
    ASSERT_EQ(summary.status, Status::kConverged) << summary.brief_report();
    EXPECT_EQ(summary.factorizations, 1) << "every angle and step shares the floating body's factorization";
    for (const TribometerAngleResult& a : summary.angles) {
      SCOPED_TRACE(lc.name + " at " + std::to_string(a.angle_degrees));
      ASSERT_TRUE(a.gross_sliding);
      ASSERT_TRUE(a.steady_sliding) << "the limit equilibrium was not found";
      const double theta = a.angle_degrees * std::numbers::pi / 180.0;
      const double capacity =
          lc.law.max_step(Eigen::Vector2d::Zero(), 1.0, Eigen::Vector2d(std::cos(theta), std::sin(theta))) * e.normal_force;
      const double error = std::abs(a.onset_force - capacity) / capacity;
      // Stick fraction along the ramp at the last ramp point below 90 % of the onset.
      double stick_at_90 = 1.0;
      for (const TribometerRampPoint& pt : a.ramp)
        if (pt.pull <= 0.9 * a.onset_force) stick_at_90 = pt.stick_fraction;
      std::printf("| %s | %.2f | %.9e | %.9e | %.1e | %.4f | %.4f | %.1e | %.3f |\n", lc.name.c_str(),
                  a.angle_degrees, a.onset_force, capacity, error, a.force_angle_degrees, a.slip_angle_degrees,
                  a.normality_residual, stick_at_90);
      EXPECT_LE(error, 1e-3);
      EXPECT_LE(a.coefficient_error, 1e-3);
      EXPECT_LE(a.onset_force, capacity * (1.0 + 1e-12)) << "an equilibrium beyond the capacity";
      EXPECT_NEAR(a.onset_normal_force, e.normal_force, 1e-9 * e.normal_force);
      // The friction force balances the pull: its direction is θ.
      EXPECT_NEAR(std::remainder(a.force_angle_degrees - a.angle_degrees, 360.0), 0.0, 1e-6);
      // Normality is NOT asserted: the limit state still has elastic slip gradients (the
      // increment from the last ramp point), so its mean slip need not be in the normal cone.
      // The stick zone shrinks along the ramp (Cattaneo–Mindlin) and is gone at the onset.
      for (std::size_t k = 1; k < a.ramp.size(); ++k)
        EXPECT_LE(a.ramp[k].stick_fraction, a.ramp[k - 1].stick_fraction + 1e-12) << "ramp point " << k;
      EXPECT_GT(a.ramp.front().stick_fraction, 0.0);
    }
  }
}

TEST(TribometerForceDrive, BelowTheCapacityNoSliding) {
  TribometerDefinition e;
  e.drive = TribometerDrive::kForce;
  e.normal_force = 1e4;
  e.max_force_ratio = 0.25;  // below μ = 0.3
  e.ramp_steps = 5;
  e.angles_degrees = {20.0};
  Tribometer tribometer(floating_specimen(FrictionLaw::disc(0.3)), e);
  const Tribometer::Summary summary = tribometer.run();
  ASSERT_EQ(summary.status, Status::kConverged) << summary.brief_report();
  const TribometerAngleResult& a = summary.angles.front();
  EXPECT_FALSE(a.gross_sliding);
  ASSERT_EQ(a.ramp.size(), 5u);
  EXPECT_NEAR(a.ramp.back().tangential_force.norm(), 0.25 * e.normal_force, 1e-8 * e.normal_force);
}

TEST(TribometerForceDrive, BadExperimentIsInvalidInput) {
  TribometerDefinition e;
  e.drive = TribometerDrive::kForce;
  e.normal_force = 1e4;
  e.max_force_ratio = 0.0;
  EXPECT_THROW(Tribometer(floating_specimen(FrictionLaw::disc(0.3)), e), InvalidInput);
  e.max_force_ratio = 0.5;
  e.onset_tolerance = 0.5;
  EXPECT_THROW(Tribometer(floating_specimen(FrictionLaw::disc(0.3)), e), InvalidInput);
  EXPECT_THROW((void)parse_tribometer_drive("torque"), InvalidInput);
}

}  // namespace
}  // namespace frictopt::study
