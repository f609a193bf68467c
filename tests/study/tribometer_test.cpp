// SPDX-License-Identifier: MIT
// The virtual tribometer (docs/experiments.md §4): for every friction law, a block pressed with
// P and dragged until it slides as a whole transmits the friction force the law prescribes:
// |T|/P = μ(φ), the radial function of W at the force direction φ, and ⟨−T/P, ŝ⟩ = N_W(ŝ) for
// the slip direction ŝ (normality). Tolerance 1e-6 relative: the solver stops at
// relative increments of 1e-10, and in steady sliding every node slips by the platen's step.
#include "frictopt/study/tribometer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "frictopt/core/error.hpp"
#include "study/tribometer_specimen.hpp"

namespace frictopt::study {
namespace {

using contact::FrictionLaw;

BodyDefinition specimen(const FrictionLaw& law) { return testing::tribometer_specimen(law); }

struct LawCase {
  std::string name;
  FrictionLaw law;
  std::vector<double> angles;  // inside one normal-cone sector for polygons (see the comment above)
};

TEST(Tribometer, SlidingForceIsTheLawsFrictionForceForEveryLaw) {
  const std::vector<LawCase> cases = {
      {"disc 0.3", FrictionLaw::disc(0.3), {0.0, 70.0}},
      {"16-gon 0.3", FrictionLaw::regular_polygon(0.3, 16), {11.25, 100.0}},
      {"4-gon (0.4, 0.2, 0.4, 0.2)",
       FrictionLaw::polygon({0.4, 0.2, 0.4, 0.2}),
       {30.0, 135.0, 250.0}},
      {"ellipse 8-gon (0.4, 0.2)", FrictionLaw::ellipse_polygon(0.4, 0.2, 8), {10.0, 95.0}},
      {"exact ellipse (0.4, 0.2)", FrictionLaw::ellipse(0.4, 0.2), {0.0, 30.0, 60.0, 90.0}},
  };
  TribometerDefinition e;
  e.normal_force = 1e4;
  e.pull_displacement = 2e-5;  // ≈ 30 × the elastic shear at sliding: the last steps slide steadily
  e.ramp_steps = 10;
  std::printf(
      "| law | θ [°] | onset pull [m] | P [N] | |T|/P | μ(φ) | rel. error | φ [°] | ŝ [°] | "
      "normality |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const LawCase& lc : cases) {
    e.angles_degrees = lc.angles;
    Tribometer tribometer(specimen(lc.law), e);
    const Tribometer::Summary summary = tribometer.run();
    ASSERT_EQ(summary.status, Status::kConverged) << summary.brief_report();
    EXPECT_EQ(summary.factorizations, 1);
    for (const TribometerAngleResult& a : summary.angles) {
      SCOPED_TRACE(lc.name + " at " + std::to_string(a.angle_degrees));
      std::printf("| %s | %.2f | %.2e | %.6e | %.9f | %.9f | %.1e | %.3f | %.3f | %.1e |\n",
                  lc.name.c_str(), a.angle_degrees, a.onset_pull, a.sliding_normal_force,
                  a.measured_coefficient, a.law_coefficient, a.coefficient_error,
                  a.force_angle_degrees, a.slip_angle_degrees, a.normality_residual);
      ASSERT_TRUE(a.steady_sliding);
      EXPECT_NEAR(a.sliding_normal_force, e.normal_force,
                  1e-9 * e.normal_force);  // force-controlled press
      EXPECT_LE(a.coefficient_error, 1e-6);
      EXPECT_LE(a.normality_residual, 1e-6);
      // Steady sliding: the specimen slides in the platen's direction.
      EXPECT_NEAR(std::remainder(a.slip_angle_degrees - a.angle_degrees, 360.0), 0.0, 1e-3);
    }
  }
}

TEST(Tribometer, PressReachesTheNormalForceAndRampRecordsTheStickFraction) {
  TribometerDefinition e;
  e.normal_force = 5e3;
  e.pull_displacement = 2e-6;
  e.ramp_steps = 8;
  e.angles_degrees = {0.0};
  Tribometer tribometer(specimen(FrictionLaw::disc(0.3)), e);
  const Tribometer::Summary summary = tribometer.run();
  ASSERT_EQ(summary.status, Status::kConverged) << summary.brief_report();
  const TribometerAngleResult& a = summary.angles.front();
  ASSERT_EQ(a.ramp.size(), 8u);
  for (std::size_t k = 1; k < a.ramp.size(); ++k)
    EXPECT_LE(a.ramp[k].stick_fraction, a.ramp[k - 1].stick_fraction + 1e-12);
  EXPECT_GT(a.ramp.front().stick_fraction, 0.0);
  EXPECT_TRUE(a.gross_sliding);
  EXPECT_GT(summary.press_displacement, 0.0);
  for (const TribometerRampPoint& pt : a.ramp)
    EXPECT_NEAR(pt.normal_force, e.normal_force, 1e-9 * e.normal_force);
}

TEST(Tribometer, BadExperimentIsInvalidInput) {
  TribometerDefinition e;
  e.normal_force = -1.0;
  e.pull_displacement = 1e-6;
  EXPECT_THROW(Tribometer(specimen(FrictionLaw::disc(0.3)), e), InvalidInput);
  e.normal_force = 1.0;
  e.angles_degrees.clear();
  EXPECT_THROW(Tribometer(specimen(FrictionLaw::disc(0.3)), e), InvalidInput);
  e.angles_degrees = {0.0};
  e.ramp_steps = 0;
  EXPECT_THROW(Tribometer(specimen(FrictionLaw::disc(0.3)), e), InvalidInput);
}

// Without pull_displacement the run chooses the pull from the law and the specimen (three times
// the elastic shear at sliding, μ_max·P·H/(G·A)) and ramps on until the specimen slides steadily:
// a user's guess (5× too long in one report) is no longer needed, and the law is read as with a
// well-chosen pull.
TEST(Tribometer, WithoutAPullLengthTheRunRampsToSteadySliding) {
  TribometerDefinition e;
  e.normal_force = 1e4;
  e.ramp_steps = 10;
  e.angles_degrees = {0.0, 45.0, 90.0};
  const BodyDefinition body = specimen(FrictionLaw::ellipse(0.4, 0.2));
  const double shear = 0.4 * 1e4 * body.height / (body.material.young / (2.0 * (1.0 + body.material.poisson)) *
                                                  body.shape.base_measure());
  EXPECT_NEAR(Tribometer::automatic_pull_displacement(body, e.normal_force), 3.0 * shear, 1e-12 * shear);
  Tribometer tribometer(body, e);
  const Tribometer::Summary summary = tribometer.run();
  ASSERT_EQ(summary.status, Status::kConverged) << summary.brief_report();
  EXPECT_TRUE(summary.automatic_pull);
  EXPECT_NEAR(summary.pull_displacement, 3.0 * shear, 1e-12 * shear);
  EXPECT_NE(summary.brief_report().find("pull chosen"), std::string::npos) << summary.brief_report();
  for (const TribometerAngleResult& a : summary.angles) {
    SCOPED_TRACE(a.angle_degrees);
    ASSERT_TRUE(a.steady_sliding);
    EXPECT_LE(a.coefficient_error, 1e-6);
    EXPECT_LE(a.normality_residual, 1e-6);
    // It stops once two sliding readings agree to 1e-7, well before the cap of 20 ramps.
    std::printf("θ = %.0f°: onset at step %d, stopped at step %zu, |T|/P = %.9f, μ(φ) = %.9f\n", a.angle_degrees,
                a.onset_step + 1, a.ramp.size(), a.measured_coefficient, a.law_coefficient);
    EXPECT_LT(static_cast<int>(a.ramp.size()), 20 * e.ramp_steps);
  }
}

}  // namespace
}  // namespace frictopt::study
