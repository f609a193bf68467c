// SPDX-License-Identifier: MIT
// The virtual tribometer with a friction law turned relative to the specimen (docs/experiments.md
// §4): for every 3D law W turned by φ = 30°, the block dragged until it slides as a whole transmits
// |T|/P = μ(ψ − φ), the UNTURNED law's radial function at the force direction ψ minus φ, and the
// slip exposes the force (normality). Tolerance 1e-6 relative, as the unturned test.
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

BodyDefinition specimen(const FrictionLaw& law) { return testing::tribometer_specimen(law); }

struct LawCase {
  std::string name;
  FrictionLaw law;             // unturned
  std::vector<double> angles;  // in the unturned law's frame; inside one normal-cone sector for polygons
};

TEST(TribometerWithATurnedLaw, SlidingForceIsTheUnturnedLawsAtTheShiftedAngle) {
  constexpr double kDegree = std::numbers::pi / 180.0;
  const double phi_deg = 30.0;
  const std::vector<LawCase> cases = {
      {"disc 0.3", FrictionLaw::disc(0.3), {0.0, 70.0}},
      {"16-gon 0.3", FrictionLaw::regular_polygon(0.3, 16), {11.25, 100.0}},
      {"4-gon (0.4, 0.2, 0.4, 0.2)", FrictionLaw::polygon({0.4, 0.2, 0.4, 0.2}), {30.0, 135.0, 250.0}},
      {"ellipse 8-gon (0.4, 0.2)", FrictionLaw::ellipse_polygon(0.4, 0.2, 8), {10.0, 95.0}},
      {"exact ellipse (0.4, 0.2)", FrictionLaw::ellipse(0.4, 0.2), {0.0, 30.0, 60.0, 90.0}},
  };
  TribometerDefinition e;
  e.normal_force = 1e4;
  e.pull_displacement = 2e-5;
  e.ramp_steps = 10;
  std::printf("| law turned by %.0f° | θ [°] | |T|/P | μ₀(ψ − φ) | rel. error | ψ [°] | ŝ [°] | normality |\n", phi_deg);
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const LawCase& lc : cases) {
    e.angles_degrees.clear();
    for (double a : lc.angles) e.angles_degrees.push_back(a + phi_deg);  // the same sectors, turned
    Tribometer tribometer(specimen(lc.law.rotated(phi_deg * kDegree)), e);
    const Tribometer::Summary summary = tribometer.run();
    ASSERT_EQ(summary.status, Status::kConverged) << summary.brief_report();
    EXPECT_EQ(summary.factorizations, 1);
    for (const TribometerAngleResult& a : summary.angles) {
      SCOPED_TRACE(lc.name + " at " + std::to_string(a.angle_degrees));
      ASSERT_TRUE(a.steady_sliding);
      // The unturned law at ψ − φ: the largest t with t·(cos, sin)(ψ − φ) ∈ W.
      const double psi = a.force_angle_degrees * kDegree, shifted = psi - phi_deg * kDegree;
      const double mu0 = lc.law.max_step(Eigen::Vector2d::Zero(), 1.0, Eigen::Vector2d(std::cos(shifted), std::sin(shifted)));
      const double error = std::abs(a.measured_coefficient - mu0) / mu0;
      std::printf("| %s | %.2f | %.9f | %.9f | %.1e | %.3f | %.3f | %.1e |\n", lc.name.c_str(), a.angle_degrees,
                  a.measured_coefficient, mu0, error, a.force_angle_degrees, a.slip_angle_degrees, a.normality_residual);
      EXPECT_LE(error, 1e-6);
      EXPECT_LE(a.coefficient_error, 1e-6);  // against the turned law's own μ(ψ)
      EXPECT_LE(a.normality_residual, 1e-6);
      EXPECT_NEAR(std::remainder(a.slip_angle_degrees - a.angle_degrees, 360.0), 0.0, 1e-3);
    }
  }
}

TEST(TribometerWithATurnedLaw, RefusesATiltedFoundation) {
  BodyDefinition def = specimen(FrictionLaw::disc(0.3));
  def.contact->foundation.offset = 1e-3;
  TribometerDefinition e;
  e.normal_force = 1e3;
  e.pull_displacement = 1e-6;
  try {
    Tribometer tribometer(def, e);
    ADD_FAILURE() << "a tribometer on a moved foundation was accepted";
  } catch (const InvalidInput& error) {
    EXPECT_NE(std::string(error.what()).find("needs the default foundation"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace frictopt::study
