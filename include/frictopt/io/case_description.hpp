// SPDX-License-Identifier: MIT
// The validated content of a case file as plain data: geometry, mesh, material, boundary
// conditions, design, contact and output settings. The schema is in docs/case-format.md; the
// parser is io/case_file.hpp. io knows no numeric module, so the enums below are io's own;
// the lead maps them onto the numeric modules' types.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/study/identification.hpp"

namespace frictopt::io {

/// A face of the body's bounding box that can carry a load or a Dirichlet condition.
/// The bottom is the contact surface Γ_c (the Bézier graph) and is not a face here.
enum class Face {
  kLeft,   ///< x1 = 0
  kRight,  ///< x1 = a
  kFront,  ///< x2 = 0 (3D only)
  kBack,   ///< x2 = b (3D only)
  kTop     ///< x_dim = height (C4)
};
/// "left", "right", "front", "back", "top".
std::string_view to_string(Face face);
/// Inverse of to_string; throws InvalidInput naming the accepted spellings.
Face parse_face(std::string_view text);

/// 2D elasticity model (spec 01 §2.5, assumption A-PS). Ignored in 3D.
enum class PlaneModel { kPlaneStrain, kPlaneStress };
/// "plane_strain", "plane_stress".
std::string_view to_string(PlaneModel model);
PlaneModel parse_plane_model(std::string_view text);

/// Scaling of the slope bound between neighbouring control points (spec 01 §4.3):
/// kThesis: |α_{i+1} − α_i| ≤ C1/(m−1); kExact: |α_{i+1} − α_i| ≤ a·C1/(m−1) (b in x2).
enum class SlopeScaling { kThesis, kExact };
/// "thesis", "exact".
std::string_view to_string(SlopeScaling scaling);
SlopeScaling parse_slope_scaling(std::string_view text);

/// The contact law on Γ_c; only Coulomb friction for now.
enum class ContactLaw { kCoulomb };
/// "coulomb".
std::string_view to_string(ContactLaw law);
ContactLaw parse_contact_law(std::string_view text);

/// Shape of the friction set P (DESIGN.md, "Friction sets").
enum class FrictionKind {
  kNone,          ///< frictionless
  kIsotropic,     ///< 2D: interval [−μ, μ]; 3D: regular n-gon μ·P_n
  kPolygon,       ///< 2D: interval [−μ_minus, μ_plus]; 3D: n-gon with per-vertex μ_j
  kEllipse,       ///< 3D: n-gon with vertices on the ellipse (μ_x, μ_y)
  kEllipseExact,  ///< 3D: the ellipse (μ_x, μ_y) itself
  kDiscExact      ///< 3D: the disc of radius μ itself
};
/// "none", "isotropic", "polygon", "ellipse", "ellipse_exact", "disc_exact".
std::string_view to_string(FrictionKind kind);
FrictionKind parse_friction_kind(std::string_view text);

/// [geometry]: the body Ω(α) = (0,a)×(0,b)×(G_α, height) (spec 01 §2.1, §3). Metres.
struct GeometrySpec {
  int dim = 2;          ///< 2 or 3
  double a = 0.0;       ///< length in x1, > 0
  double b = 0.0;       ///< length in x2, > 0 in 3D; 0 in 2D (the key is forbidden there)
  double height = 0.0;  ///< C4, the height of the flat top, > 0
};

/// [mesh]: the structured reference grid.
struct MeshSpec {
  /// Number of cells per direction, each >= 1: {n1, n_vertical} in 2D, {n1, n2, n_vertical}
  /// in 3D (so cells.size() == dim and cells.back() is the vertical count).
  std::vector<int> cells;
  /// Vertical bias toward the contact surface, in [1, 10]; 1 = uniform. The mesh module
  /// defines the exact law (e.g. the ratio of the top to the bottom cell height).
  double grading = 1.0;
};

/// [material]: isotropic linear elasticity.
struct MaterialSpec {
  double young = 0.0;                           ///< Young's modulus E [Pa], > 0
  double poisson = 0.0;                         ///< Poisson's ratio ν, 0 <= ν < 0.5
  PlaneModel model = PlaneModel::kPlaneStrain;  ///< 2D only
};

/// One [[load]]: a dead traction on a face, force per current area [N/m²].
struct LoadSpec {
  Face face = Face::kTop;
  Eigen::VectorXd traction;  ///< dim components
};

/// One [[dirichlet]]: prescribed displacement components on a face [m].
struct DirichletSpec {
  Face face = Face::kLeft;
  Eigen::VectorXd displacement;  ///< dim components (all of them; only `components` apply)
  std::vector<int> components;   ///< fixed components, strictly increasing, each in [0, dim)
};

/// [design]: the Bézier control net α and the admissible set Υ (spec 01 §4, A-3DUPS).
struct DesignSpec {
  /// {m1} in 2D, {m1, m2} in 3D; each >= 2. α has m1·m2 entries, row-major, x1 fastest.
  std::vector<int> control_points;
  /// The initial design α⁰ [m], expanded to num_control_points() entries, each in [0, C0].
  Eigen::VectorXd initial;
  double upper_bound = 0.0;  ///< C0 [m], 0 < C0 < geometry.height
  /// C1, the slope bound (> 0); absent: no slope rows in Υ.
  std::optional<double> slope_bound;
  /// C2, the prescribed area (2D, m²) or volume (3D, m³) of Ω(α); absent: no volume
  /// equality. When present it lies in [A·(height − C0), A·height], A = a (2D) or a·b (3D),
  /// the range reachable with 0 <= α <= C0.
  std::optional<double> volume;
  SlopeScaling slope_scaling = SlopeScaling::kThesis;

  /// m1 (2D) or m1·m2 (3D): the length of α (the parser bounds it, docs/case-format.md
  /// "Size limits", so it fits an int).
  [[nodiscard]] int num_control_points() const;
};

/// [contact.friction].
struct FrictionSpec {
  FrictionKind kind = FrictionKind::kNone;
  /// kIsotropic, kDiscExact: the coefficient μ >= 0.
  std::optional<double> mu;
  /// 3D kIsotropic, kPolygon, kEllipse: the number of polygon sides, >= 3 (16 by default for
  /// kIsotropic and kEllipse; for kPolygon it equals mu_vertices.size()).
  std::optional<int> n;
  /// 3D kPolygon: the coefficient μ_j >= 0 of vertex j (vertex μ_j·v_j, DESIGN.md).
  std::vector<double> mu_vertices;
  /// 3D kEllipse, kEllipseExact: the semi-axes along x1 and x2, each >= 0.
  std::optional<double> mu_x;
  std::optional<double> mu_y;
  /// 2D kPolygon: coefficients for slip in +x1 and in −x1, each >= 0.
  std::optional<double> mu_plus;
  std::optional<double> mu_minus;
};

/// [contact]: present iff the body is in contact with the rigid foundation x_dim <= 0.
struct ContactSpec {
  ContactLaw law = ContactLaw::kCoulomb;
  FrictionSpec friction;  ///< kind kNone when [contact.friction] is absent
};

/// Options of an iterative solver that a case may override. Absent fields keep the
/// consuming module's own defaults.
struct IterativeSolverSpec {
  std::optional<int> max_iterations;         ///< >= 1
  std::optional<double> relative_tolerance;  ///< > 0
};

/// [solver]: overrides of solver options. [solver.fem] is reserved and must be empty.
struct SolverSpec {
  IterativeSolverSpec coulomb;  ///< [solver.coulomb]: the Coulomb fixed point
  IterativeSolverSpec qp;       ///< [solver.qp]: the Tresca dual QP
};

/// [cost]: the cost functional J (spec 05 §2.4, issue 6).
enum class CostKind {
  kTargetPressure,    ///< Σ(λ̄ − λ)² with λ̄_i = p̄·a_i (thesis ex. 5.2.1)
  kNormalForcePower,  ///< Σ λ_i^p (thesis ex. 5.2.2 with p = 4)
  kCompliance,        ///< −uᵀAu + lᵀu (thesis ex. 5.2.3)
  kPressureNorm,      ///< (Σ a_i p_i^p)^{1/p}: smooth peak-pressure surrogate
  kTotalSlip,         ///< Σ √(|u_t|² + δ²) − δ
  kTractionUniformity ///< Σ a_i ‖t_i − t̄‖²: tangential traction about a target or its mean
};
/// "target_pressure", "normal_force_power", "compliance", "pressure_norm", "total_slip",
/// "traction_uniformity".
std::string_view to_string(CostKind kind);
CostKind parse_cost_kind(std::string_view text);

struct CostSpec {
  CostKind kind = CostKind::kCompliance;
  /// kTargetPressure: a uniform target pressure p̄ [Pa]; absent with target_initial_mean: the
  /// initial total normal force spread as a uniform pressure (spec 05 §2.3).
  std::optional<double> target_pressure;
  bool target_initial_mean = false;
  std::optional<double> exponent;   ///< kNormalForcePower (default 4), kPressureNorm (default 8); >= 2
  std::optional<double> smoothing;  ///< kTotalSlip: δ > 0 [m] (default 1e-6)
  /// kTractionUniformity: target tangential traction [Pa], dim − 1 components; absent or
  /// target = "mean": the current area-weighted mean traction.
  std::vector<double> target_traction;
  /// kTractionUniformity with target = "initial_mean": t̄ = the mean traction at α⁰, fixed.
  bool target_traction_initial_mean = false;
};

/// [optimization]: bundle trust options a case may override (absent: the method's defaults).
struct OptimizationSpec {
  std::optional<int> max_iterations;     ///< >= 1
  std::optional<int> max_evaluations;    ///< >= 1
  std::optional<double> epsilon;         ///< stopping tolerance ε > 0
  std::optional<double> max_step_length; ///< T: largest trust-region radius [m] > 0
  std::optional<int> bundle_size;        ///< j_max >= 3
};

/// [output].
struct OutputSpec {
  bool vtk = true;   ///< write .vtu (and a .pvd for series)
  int every = 1;     ///< write every n-th optimization iterate, >= 1
  std::string name;  ///< base name of output files; default the case file stem
};


/// One [identification.parameters.<name>] table: a parameter (group) to identify. `name` is
/// "young" or a coefficient of the case's friction kind: "mu" (isotropic, disc_exact),
/// "mu_vertices" (3D polygon: one parameter per vertex), "mu_x", "mu_y" (ellipse kinds),
/// "mu_plus", "mu_minus" (2D polygon).
struct IdentifiedParameterSpec {
  std::string name;
  std::vector<double> initial;  ///< empty: the case's value(s); else 1 entry or one per vertex
  std::vector<double> lower;    ///< 1 entry (every vertex) or one per vertex; >= 0 (young: > 0)
  std::vector<double> upper;    ///< idem; lower <= initial <= upper entrywise
};

/// [identification]: identify friction coefficients (and E) from measurements (docs/identification.md).
struct IdentificationSpec {
  /// The measurement CSV; a relative path is resolved against the case file's directory.
  std::filesystem::path measurements;
  std::vector<IdentifiedParameterSpec> parameters;  ///< at least one, in the file's order
  study::RobustLoss loss = study::RobustLoss::kNone;  ///< robust loss on each normalized residual
  double loss_scale = 1.0;            ///< > 0, in standard deviations
  std::optional<int> max_iterations;  ///< >= 1
};

/// A validated case: every field satisfies the ranges documented above, and the
/// dimension-dependent sizes (cells, traction, displacement, control_points) match
/// geometry.dim. Consumers may trust it without re-validating.
struct CaseDescription {
  std::string origin;  ///< where it came from (file path or origin name), for messages
  GeometrySpec geometry;
  MeshSpec mesh;
  MaterialSpec material;
  std::vector<LoadSpec> loads;           ///< [[load]], possibly empty; loads on a face add up
  std::vector<DirichletSpec> dirichlet;  ///< [[dirichlet]], at least one
  DesignSpec design;
  std::optional<ContactSpec> contact;  ///< absent: no contact
  SolverSpec solver;
  std::optional<CostSpec> cost;                  ///< absent: only `solve` is possible
  OptimizationSpec optimization;
  OutputSpec output;
  std::optional<IdentificationSpec> identification;  ///< [identification], absent: no `identify`
  /// The problem the case defines, normalized: every key of the file except the run controls
  /// [optimization] and [output], as dotted key ("material.young", "load[0].traction") ->
  /// canonical value text (numbers in shortest round-trip form, so 7e10 and 70000000000.0
  /// agree; comments, layout and key order do not matter). A run's checkpoint stores it to
  /// refuse resuming a different problem (io/checkpoint.hpp).
  std::map<std::string, std::string> problem_settings;
};

}  // namespace frictopt::io
