// SPDX-License-Identifier: MIT
// A virtual tribometer (issue 12, item 4; docs/experiments.md): a rigid platen glued to the
// specimen's top face presses it onto the foundation until the normal force is P, then drags it
// sideways in direction θ, ramping the displacement until the specimen slides as a whole. Per θ
// it records the tangential force at the onset of gross sliding, its direction, the slip
// direction and the stick-area fraction along the ramp: the measured friction polar, compared
// with the law's μ(θ) (the radial function of W) and its normality rule.
//
// All angles and all ramp steps are solved on ONE factorization: the platen fixes the same DOFs
// (every component of the top face) in every step; only the prescribed values change, which
// enter the right-hand side through the lifting (ElasticBody::solve_step).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "frictopt/core/status.hpp"
#include "frictopt/study/body_definition.hpp"

namespace frictopt::study {

/// [experiment] of a case.
struct TribometerDefinition {
  double normal_force = 0.0;                ///< P [N] pressed by the platen; > 0
  double pull_displacement = 0.0;           ///< final tangential platen displacement [m]; > 0
  std::vector<double> angles_degrees{0.0};  ///< pull directions θ in the (x1, x2) plane
  int ramp_steps = 20;                      ///< ramp increments from 0 to pull_displacement; >= 1
  /// Throws InvalidInput naming "experiment.<field>".
  void validate() const;
};

/// One point of the ramp at one angle.
struct TribometerRampPoint {
  double pull = 0.0;                                           ///< platen displacement [m]
  double normal_force = 0.0;                                   ///< P [N]
  Eigen::Vector2d tangential_force = Eigen::Vector2d::Zero();  ///< T on the specimen [N]
  double stick_fraction = 0.0;                                 ///< stick area / contact area
  int num_stick = 0, num_slip = 0;
};

/// The result at one angle θ. The platen's pull direction θ is the direction in which the
/// specimen slides once it slides as a whole: each later ramp step moves every contact node by
/// the platen's increment. The friction law is read there ("sliding" fields, at the last ramp
/// step): the force P·w must be the point w ∈ ∂N_W(ŝ) of W exposed by the slip direction ŝ
/// (normality rule), so |T|/P = μ(φ), the radial function of W at the force direction φ, and
/// ⟨−T/P, ŝ⟩ = N_W(ŝ), the law's resistance to sliding along ŝ.
struct TribometerAngleResult {
  double angle_degrees = 0.0;  ///< the platen's pull direction θ
  std::vector<TribometerRampPoint> ramp;
  bool gross_sliding = false;        ///< some ramp step has no stick node
  int onset_step = -1;               ///< first ramp index (0-based) without stick nodes
  double onset_pull = kNaN;          ///< platen displacement at onset [m]
  double onset_force = kNaN;         ///< |T| at onset [N]
  double onset_normal_force = kNaN;  ///< P at onset [N]
  bool steady_sliding = false;  ///< gross sliding in the last two ramp steps (sliding fields valid)
  double sliding_force = kNaN;  ///< |T| at the last ramp step [N]
  double sliding_normal_force = kNaN;  ///< P there [N]
  double force_angle_degrees =
      kNaN;  ///< φ: direction of the friction resistance −T (the pull force)
  double slip_angle_degrees = kNaN;    ///< ŝ: λ-weighted mean slip direction of the last step
  double measured_coefficient = kNaN;  ///< |T| / P
  double law_coefficient = kNaN;       ///< μ(φ): radial function of W at φ
  double coefficient_error = kNaN;     ///< |measured − law| / law
  double sliding_resistance = kNaN;    ///< ⟨−T/P, ŝ⟩
  double law_resistance = kNaN;        ///< N_W(ŝ), the support function
  /// Normality: |N_W(ŝ) − ⟨ŝ, −T/P⟩| / N_W(ŝ) (0 when the friction force is the point of W
  /// exposed by the slip, as the law's normality rule demands).
  double normality_residual = kNaN;
};

class Tribometer {
 public:
  struct Summary {
    Status status = Status::kNotRun;
    std::string message = "run() has not been called";
    double press_displacement = kNaN;  ///< platen indentation δ giving P [m]
    int press_iterations = 0;          ///< secant steps for δ
    int contact_solves = 0;
    int factorizations = 0;
    double time_seconds = 0.0;
    std::vector<TribometerAngleResult> angles;
    std::string brief_report() const;
  };
  using AngleCallback = std::function<void(const TribometerAngleResult&)>;

  /// `body` is the specimen: a 3D body with contact; its [[dirichlet]] tables are replaced by the
  /// platen on the face "top" and its [[load]]/[[force]] tables are kept. Throws InvalidInput.
  Tribometer(BodyDefinition body, TribometerDefinition experiment);
  [[nodiscard]] Summary run(const AngleCallback& on_angle = {});

 private:
  BodyDefinition body_;
  TribometerDefinition experiment_;
};

}  // namespace frictopt::study
