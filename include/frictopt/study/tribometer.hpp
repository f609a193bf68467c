// SPDX-License-Identifier: MIT
// A virtual tribometer (docs/experiments.md §4): a rigid platen glued to the
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
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/core/status.hpp"
#include "frictopt/study/body_definition.hpp"

namespace frictopt::study {

/// How the tribometer pulls (docs/experiments.md §4).
enum class TribometerDrive {
  /// A rigid platen glued to the top face is dragged by a ramped displacement; the measured
  /// force is the platen's reaction. Reaches steady sliding (the law read in sliding).
  kDisplacement,
  /// The specimen floats (no Dirichlet condition): the top face carries the normal force P and a
  /// ramped tangential force Q as uniform tractions; contact and friction alone hold it. The
  /// onset of gross sliding is the largest Q with a static equilibrium, bracketed by the ramp
  /// and refined by bisection (docs/experiments.md, "Pulling with a force").
  kForce
};
/// "displacement", "force".
std::string_view to_string(TribometerDrive drive);
/// Inverse of to_string; throws InvalidInput listing the accepted spellings.
TribometerDrive parse_tribometer_drive(std::string_view text);

/// Bounds of the tribometer's work (docs/case-format.md, "Size limits"): the pull directions,
/// and the ramp's contact solves over all of them (angles × ramp_steps).
inline constexpr std::size_t kMaxTribometerAngles = 10'000;
inline constexpr std::int64_t kMaxTribometerRampSolves = 1'000'000;

/// [experiment] of a case.
struct TribometerDefinition {
  TribometerDrive drive = TribometerDrive::kDisplacement;
  double normal_force = 0.0;                ///< P [N] pressed by the platen (or the top traction); > 0
  /// kDisplacement: the ramp's final tangential platen displacement [m]; > 0. Absent: chosen
  /// from the law and the specimen (Tribometer::automatic_pull_displacement) and the ramp goes on
  /// past it, step by step, until the specimen slides steadily (the reading |T|/P changes by less than 1e-7 between
  /// steps; at most 20·ramp_steps steps).
  std::optional<double> pull_displacement;
  /// kForce: the ramp's final tangential force as a multiple of P (Q_max = ratio·P); > 0. Set it
  /// above the law's largest coefficient to reach gross sliding in every direction.
  double max_force_ratio = 0.0;
  std::vector<double> angles_degrees{0.0};  ///< pull directions θ in the (x1, x2) plane
  int ramp_steps = 20;                      ///< ramp increments from 0 to the final pull; >= 1
  /// kForce: the bisection on the onset force stops at this relative bracket width (0, 1e-2].
  double onset_tolerance = 1e-6;
  /// Throws InvalidInput naming "experiment.<field>" (also beyond kMaxTribometerAngles angles or
  /// kMaxTribometerRampSolves ramp solves).
  void validate() const;
};

/// One point of the ramp at one angle.
struct TribometerRampPoint {
  double pull = 0.0;  ///< kDisplacement: platen displacement [m]; kForce: pull force Q [N]
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
  /// kDisplacement: first ramp index (0-based) without stick nodes. kForce: the first ramp
  /// index without a static equilibrium (the onset lies between it and the previous one).
  int onset_step = -1;
  double onset_pull = kNaN;          ///< kDisplacement: platen displacement at onset [m]; kForce: NaN
  /// |T| at onset [N]. kForce: the largest pull force with a static equilibrium, to the relative
  /// bracket width onset_tolerance (bisection; every trial from the last ramp equilibrium).
  double onset_force = kNaN;
  double onset_normal_force = kNaN;  ///< P at onset [N]
  /// kDisplacement: gross sliding in the last two ramp steps (sliding fields valid, at the last
  /// step). kForce: the limit equilibrium at onset_force was found (sliding fields there: the
  /// state in which every contact node is about to slide).
  bool steady_sliding = false;
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
    /// kDisplacement: the ramp's final pull [m], the case's or the automatic one (NaN: kForce).
    double pull_displacement = kNaN;
    bool automatic_pull = false;       ///< pull_displacement was chosen by the run
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

  /// The pull length chosen when the case gives none: three times the elastic shear of the
  /// specimen at sliding, δ_s = μ_max·P·H / (G·A) (the block as a column in shear: H its height,
  /// A its top area, G = E / (2(1 + ν)), μ_max the law's largest support N_W(e_θ)). The onset of
  /// gross sliding lies near δ_s (the stick zone shrinks from the rim as the pull grows), so the
  /// ramp's first third holds the stick–slip transition and the rest the sliding.
  [[nodiscard]] static double automatic_pull_displacement(const BodyDefinition& specimen, double normal_force);

 private:
  /// TribometerDrive::kForce (tribometer_force_ramp.cpp).
  [[nodiscard]] Summary run_force_ramp(const AngleCallback& on_angle);

  BodyDefinition body_;
  TribometerDefinition experiment_;
};

}  // namespace frictopt::study
