// SPDX-License-Identifier: MIT
// Identification of friction coefficients (and optionally Young's modulus) from measured contact
// quantities (docs/identification.md): weighted nonlinear least squares with Ceres, Jacobians from
// our forward sensitivities (sensitivity/parameter_sensitivity.hpp), parameter covariance and an
// identifiability report. Ceres stays inside src/study; this header names none of its types.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/core/status.hpp"
#include "frictopt/study/body_definition.hpp"

namespace frictopt::study {

/// A measurable contact quantity. Node quantities read contact node i; totals sum over all
/// contact nodes. Signs: forces and tractions are those the foundation exerts on the body
/// (τ = −q, docs/theory/state-problem.md §1); slips are the tangential displacements u_t of the
/// node [m].
enum class MeasuredQuantity {
  kNormalForce,             ///< λ_i [N] (2D: N per metre of thickness)
  kPressure,                ///< λ_i / a_i [Pa], a_i the tributary area
  kTangentialForceX1,       ///< τ_i,1 [N]
  kTangentialForceX2,       ///< τ_i,2 [N] (3D)
  kTractionX1,              ///< τ_i,1 / a_i [Pa]
  kTractionX2,              ///< τ_i,2 / a_i [Pa] (3D)
  kSlipX1,                  ///< u_t,1 of node i [m]
  kSlipX2,                  ///< u_t,2 of node i [m] (3D)
  kTotalNormalForce,        ///< Σ_i λ_i [N]
  kTotalTangentialForceX1,  ///< Σ_i τ_i,1 [N]
  kTotalTangentialForceX2   ///< Σ_i τ_i,2 [N] (3D)
};
/// "normal_force", "pressure", "tangential_force_x1", "tangential_force_x2", "traction_x1",
/// "traction_x2", "slip_x1", "slip_x2", "total_normal_force", "total_tangential_force_x1",
/// "total_tangential_force_x2".
std::string_view to_string(MeasuredQuantity quantity);
/// Inverse of to_string; throws InvalidInput listing the accepted spellings.
MeasuredQuantity parse_measured_quantity(std::string_view text);
/// True for the sums over Γ_c (they take no location).
bool is_total(MeasuredQuantity quantity);

/// Bounds of an identification (docs/case-format.md, "Size limits"; docs/identification.md,
/// "Limits"): the measurements (each a residual and a row of the dense Jacobian), the sums over
/// Γ_c among them (each a row with one entry per contact node), and the contact unknowns dim·p
/// (the dense Delassus matrix has (dim·p)² entries: 3.2 GB at the bound).
inline constexpr std::size_t kMaxMeasurements = 100'000;
inline constexpr std::size_t kMaxTotalMeasurements = 1'000;
inline constexpr std::int64_t kMaxIdentificationContactUnknowns = 20'000;
/// Experiments of one identification: each holds its own factorization and dense Delassus matrix.
inline constexpr std::size_t kMaxIdentificationExperiments = 100;

/// One measured value with its standard deviation.
struct Measurement {
  MeasuredQuantity quantity = MeasuredQuantity::kNormalForce;
  /// Contact-node index (0-based, the order of contact::ContactBoundary::nodes()), or −1.
  int node = -1;
  /// Or: in-plane coordinates x' (dim − 1 entries) [m]; the nearest contact node is used.
  std::optional<Eigen::VectorXd> point;
  double value = 0.0;  ///< in the quantity's unit
  double sigma = 1.0;  ///< standard deviation, > 0, same unit
  std::string label;   ///< where it came from, for messages ("measurements.csv:7")
};

/// One experiment of an identification (docs/identification.md, "Several experiments"): the case's
/// body at its initial design under its own loads — the case's [[load]], [[dirichlet]] and
/// [[force]] tables scaled as a load case scales them (study/load_case_definition.hpp) — with the
/// friction law turned by `orientation` in the contact plane (the specimen turned on the
/// tribometer: FrictionLaw::rotated, docs/theory/friction-frame.md), and its own measurements.
/// The identified parameters are the coefficients of the law in the specimen's own frame, shared
/// by every experiment: one experiment may leave a coefficient undetermined (sliding along the
/// lay reads only μ along the lay) that another determines.
struct IdentificationExperiment {
  std::string name = "experiment";      ///< for reports; unique among the experiments
  /// Scale factors: one per BodyDefinition::tractions / dirichlet (its displacement) / forces, or a
  /// single one for every table of its kind; empty: every scale 1.
  std::vector<double> load_scale;
  std::vector<double> dirichlet_scale;
  std::vector<double> force_scale;
  double orientation = 0.0;             ///< [rad], added to the law's own orientation (3D laws)
  std::vector<Measurement> measurements;  ///< non-empty
};

/// Robust loss on each normalized residual r = (model − value)/σ (Ceres' HuberLoss, CauchyLoss).
enum class RobustLoss { kNone, kHuber, kCauchy };
/// "none", "huber", "cauchy".
std::string_view to_string(RobustLoss loss);
RobustLoss parse_robust_loss(std::string_view text);

/// One parameter to identify, by name: a friction parameter of the case's law
/// (sensitivity::friction_parameters names: "mu", "mu_vertices[j]", "mu_x", "mu_y",
/// "mu_minus", "mu_plus") or "young". The others stay at the case's values.
struct ParameterSpec {
  std::string name;
  double initial = kNaN;  ///< starting value; NaN: the case's value
  double lower = 0.0;     ///< bounds, lower <= initial <= upper (friction: lower >= 0; young: lower > 0)
  double upper = 1.0;
};

/// How well the data determine one parameter at the estimate.
enum class Identifiability {
  kDetermined,     ///< full-rank Jacobian: the standard deviation is meaningful
  kAtBound,        ///< the estimate sits on a bound: the deviation is that of the free problem
  kNotDetermined,  ///< the Jacobian column is (numerically) zero: no measurement depends on it
  kCorrelated      ///< only a combination with other parameters is determined (rank deficient)
};
/// "determined", "at_bound", "not_determined", "correlated".
std::string_view to_string(Identifiability identifiability);

/// Weighted least squares  min_p ½ Σ_i ρ(((model_i(p) − value_i)/σ_i)²)  over lower <= p <= upper,
/// where model_i reads the contact state of the case's body at its initial design with the
/// friction law's parameters (and E) set to p — under the loads and turned law of measurement i's
/// experiment (IdentificationExperiment; one experiment: the case's own loads). The state map is piecewise smooth; the Jacobian
/// is that of the default piece (docs/theory/sensitivity.md §4) by forward sensitivities
/// (sensitivity::contact_state_derivative), so one Coulomb solve and one contact-sized LU per
/// trial point. E enters through M(E) = (E₀/E) M₀ and the free response, which is exact for
/// linear elasticity (A and the Dirichlet lifting scale with E).
///
/// Lifetime: owns its body. Not thread-safe. The dense Delassus matrix is assembled once, so the
/// contact set must be small enough for a dense dim·p × dim·p matrix.
class Identification {
 public:
  struct Options {
    std::vector<ParameterSpec> parameters;  ///< non-empty, distinct names
    RobustLoss loss = RobustLoss::kNone;
    double loss_scale = 1.0;      ///< a in ρ (Huber: quadratic for |r| <= a); > 0, in σ units
    int max_iterations = 100;     ///< Levenberg–Marquardt iterations, >= 1
    /// Ceres' stopping tolerances (Solver::Options): relative cost decrease, relative step,
    /// and max-norm of the projected gradient. Tight: the noise-free test recovers to 1e-6.
    double function_tolerance = 1e-14;
    double parameter_tolerance = 1e-12;
    double gradient_tolerance = 1e-16;
    /// The Coulomb solve per trial point uses min(case tolerance, this) for the fixed point and
    /// the inner QP: the Jacobian is exact only if the state is accurate to well below the step
    /// Ceres takes. In (0, 1).
    double state_tolerance = 1e-13;
    /// A parameter whose scaled Jacobian column (∂r/∂(p/scale)) has norm below this is not
    /// determined: a 100% change of it moves the normalized residuals by less than this.
    double zero_column_tolerance = 1e-10;
    /// Smallest singular value / largest of the scaled Jacobian below which it is rank deficient.
    double rank_tolerance = 1e-10;
    void validate() const;  ///< throws InvalidInput naming field, value and expectation
  };

  struct ParameterEstimate {
    std::string name;
    double initial = kNaN;
    double value = kNaN;
    double lower = kNaN, upper = kNaN;
    /// From ceres::Covariance; NaN when the parameter is not determined (see `identifiability`).
    double standard_deviation = kNaN;
    Identifiability identifiability = Identifiability::kNotDetermined;
    std::string note;  ///< e.g. "only a lower bound: mu >= 0.214 (every contact node sticks)"
  };

  struct Summary {
    Status status = Status::kNotRun;
    std::string message = "run() has not been called";
    std::string ceres_brief_report;  ///< ceres::Solver::Summary::BriefReport()
    std::string ceres_full_report;   ///< ceres::Solver::Summary::FullReport()
    int iterations = 0;
    int state_solves = 0;             ///< Coulomb solves (one per distinct trial point)
    int jacobian_evaluations = 0;
    double initial_cost = kNaN;       ///< ½ Σ ρ(r_i²) at the start
    double final_cost = kNaN;
    double chi_square = kNaN;         ///< Σ r_i² at the estimate (without the robust loss)
    int degrees_of_freedom = 0;       ///< measurements − parameters
    std::vector<ParameterEstimate> estimates;
    Eigen::MatrixXd covariance;       ///< of the parameters (physical units); NaN rows/cols where undetermined
    Eigen::MatrixXd correlation;      ///< idem, normalized
    Eigen::VectorXd singular_values;  ///< of the scaled Jacobian at the estimate
    Eigen::VectorXd predictions;      ///< model values at the estimate, one per measurement
    Eigen::VectorXd residuals;        ///< (model − value)/σ at the estimate
    std::string index_sets;           ///< contact index sets at the estimate ("name: ..." per experiment)
    /// One per experiment, in order: its share of the fit at the estimate.
    struct ExperimentResidual {
      std::string name;
      Eigen::Index first_measurement = 0;  ///< its rows in predictions / residuals
      Eigen::Index num_measurements = 0;
      double chi_square = kNaN;            ///< Σ r_i² over its rows
      double rms_residual = kNaN;          ///< sqrt(chi_square / num_measurements)
      int num_slipping_nodes = 0;          ///< at the estimate
      std::string index_sets;              ///< at the estimate
    };
    std::vector<ExperimentResidual> experiments;
    double time_seconds = 0.0;
    std::string brief_report() const;
  };

  /// Model values and their Jacobian at a parameter vector (the experiments' rows stacked in order).
  struct Prediction {
    bool ok = false;
    std::string message;
    Eigen::VectorXd values;    ///< one per measurement
    Eigen::MatrixXd jacobian;  ///< ∂values/∂p (measurements × parameters); empty unless requested
    contact::CoulombSolver::Summary contact;  ///< of the first experiment (the one failing, if any)
    std::string index_sets;                   ///< one experiment: its sets; several: "name: sets; ..."
    int num_slipping_nodes = 0;               ///< over all experiments
  };

  /// Validates the options and measurements against the body: parameter names for its law,
  /// bounds, σ > 0, finite values, node indices and locations on Γ_c, 3D-only quantities.
  /// Throws InvalidInput naming the item ("measurements.csv:7: node = 400; expected a contact
  /// node index in [0, 81)"). Solves the elasticity at the initial design once (factorization
  /// and Delassus matrix); throws InvalidInput when the body has no contact or cannot be factorized.
  Identification(BodyDefinition definition, std::vector<Measurement> measurements, Options options);
  /// Several experiments on the same body (IdentificationExperiment): each has its own state
  /// operators (its loads and turned law; one factorization each) and its own residual blocks,
  /// and the least-squares problem sums them all. As above, plus InvalidInput for no experiment,
  /// an empty or duplicate name, a scale list of the wrong length or a non-finite scale, a
  /// non-finite orientation or a nonzero one on a 2D law, an experiment without measurements
  /// (messages name "experiment[k] (\"name\")").
  Identification(BodyDefinition definition, std::vector<IdentificationExperiment> experiments, Options options);
  ~Identification();
  Identification(const Identification&) = delete;
  Identification& operator=(const Identification&) = delete;

  const std::vector<std::string>& parameter_names() const;
  /// The starting point (the options' initial values, or the case's).
  Eigen::VectorXd initial_parameters() const;
  /// The body definition's own values of the parameters (its friction law and E): the "true"
  /// values when synthetic data are generated from the case.
  Eigen::VectorXd case_parameters() const;
  /// In-plane coordinates x' of the contact nodes (p × dim−1), for reports and plots.
  const Eigen::MatrixXd& contact_coordinates() const;
  /// The measurements with their locations resolved to contact nodes (node >= 0 or totals), the
  /// experiments' rows in order.
  const std::vector<Measurement>& measurements() const;
  /// The experiments' names, and for each measurement the index of its experiment.
  const std::vector<std::string>& experiment_names() const;
  const std::vector<int>& measurement_experiment() const;

  /// The model at `parameters` (one per parameter name); the Jacobian by forward sensitivities.
  /// A failed state solve or an invalid law (e.g. non-convex polygon) gives ok = false.
  [[nodiscard]] Prediction predict(const Eigen::Ref<const Eigen::VectorXd>& parameters, bool with_jacobian = false);

  /// Runs Levenberg–Marquardt from initial_parameters(), then the covariance and the
  /// identifiability report. Non-convergence is a status.
  [[nodiscard]] Summary run();

  /// Implementation detail (defined in src/study/identification.cpp, where the Ceres cost
  /// functions reach it); not part of the interface.
  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

/// Synthetic measurements: `templates` (quantity, location, σ) with values = `exact` (one per
/// template, e.g. Identification::predict at the true parameters) plus, when `add_noise`,
/// Gaussian noise N(0, σ²) from std::mt19937_64(seed).
std::vector<Measurement> synthetic_measurements(const std::vector<Measurement>& templates,
                                                const Eigen::Ref<const Eigen::VectorXd>& exact, std::uint64_t seed,
                                                bool add_noise = true);

/// The experiments with every measurement's value replaced by synthetic_measurements over all
/// their rows in order (one seeded stream): `exact` holds one value per row, as
/// Identification::predict returns them for these experiments.
std::vector<IdentificationExperiment> synthetic_experiments(std::vector<IdentificationExperiment> experiments,
                                                            const Eigen::Ref<const Eigen::VectorXd>& exact,
                                                            std::uint64_t seed, bool add_noise = true);

}  // namespace frictopt::study
