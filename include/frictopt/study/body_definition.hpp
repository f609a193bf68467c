// SPDX-License-Identifier: MIT
// Everything that defines one body and its admissible designs, in the numeric modules' types
// (io builds it from a case file; tests build it directly).
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "frictopt/contact/contact_boundary.hpp"
#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/cost/cost_kind.hpp"
#include "frictopt/fem/boundary_conditions.hpp"
#include "frictopt/fem/loading_plate.hpp"
#include "frictopt/fem/material.hpp"
#include "frictopt/fem/node_selection.hpp"
#include "frictopt/linalg/spd_solver.hpp"
#include "frictopt/mesh/design_extension.hpp"
#include "frictopt/mesh/grid_resolution.hpp"
#include "frictopt/mesh/mesh.hpp"
#include "frictopt/shape/admissible_set.hpp"
#include "frictopt/shape/bezier_shape.hpp"
#include "frictopt/study/load_case_definition.hpp"
#include "frictopt/study/orientation_design.hpp"
#include "frictopt/study/state_engine.hpp"

namespace frictopt::study {

struct LoadingProgramDefinition;  // study/loading_program.hpp (which needs this header)

/// Unilateral contact with Coulomb friction on Γ_c against the rigid foundation (default
/// x_dim <= 0; `foundation` for any plane and law frame).
struct ContactDefinition {
  /// The friction law at every contact node (2D: an interval law; 3D: disc, polygon, ellipse).
  contact::FrictionLaw law = contact::FrictionLaw::disc(0.0);
  contact::CoulombSolver::Options coulomb;
  /// Largest number of contact unknowns m = dim·p for which M = G A⁻¹ Gᵀ is formed densely
  /// from the Schur factor L (LAPACK dpotri, 2m³/3 flops, 8m² bytes: 2.7 s and 203 MB at
  /// m = 5,043); a product is then one dsymv. Above it M is applied through L (two triangular
  /// solves per product, no m³ work). Measured at m = 5,043 (docs/benchmarks.md): dsymv 2.4 ms
  /// vs 7.6 ms for the triangular solves, so dpotri pays for itself after ≈ 520 products — a
  /// Coulomb solve takes 500–1,100 — and the sensitivity's blocks of M become free. 12,000
  /// bounds the dense M at 1.15 GB. The contact DOFs are always ordered last in the
  /// factorization so that L comes with it.
  int dense_delassus_max_unknowns = 12000;
  /// The foundation plane n·x = d and the friction law's frame in it (docs/theory/friction-frame.md
  /// §3; default n = e_dim, d = 0). A non-standard one turns the Schur factor's dense M per node
  /// (contact::turn_delassus); above dense_delassus_max_unknowns it applies M through the
  /// factorization (the Schur operator assumes the standard ±unit rows of G).
  contact::Foundation foundation;
};

/// The cost functional of a study (docs/theory/costs.md; cost module).
struct CostDefinition {
  cost::CostKind kind = cost::CostKind::kCompliance;
  /// kTargetPressure: uniform target pressure p̄ [Pa], λ̄_i = p̄·a_i; NaN: the initial total
  /// normal force spread as a uniform pressure (the reading of the thesis' target,
  /// docs/theory/costs.md).
  double target_pressure = std::numeric_limits<double>::quiet_NaN();
  double exponent = 4.0;    ///< kNormalForcePower (thesis: 4), kPressureNorm (case files: 8)
  double smoothing = 1e-6;  ///< kTotalSlip [m]
  /// kTractionUniformity: the target tangential traction t̄ [Pa] (dim − 1 components); empty:
  /// the area-weighted mean traction of the current state (J is then its variance).
  Eigen::VectorXd target_traction;
  /// kTractionUniformity: t̄ = the area-weighted mean traction at the initial design (fixed),
  /// so that J penalizes both an uneven traction and a smaller transmitted shear.
  bool target_traction_initial_mean = false;
  /// [[load_case]] + [study] (docs/theory/load-cases.md): J on each of K load cases, combined into
  /// one Θ (study/load_cases.hpp); absent: J on the case file's own loads.
  std::optional<LoadCasesDefinition> load_cases;
  /// [[program.step]] + [cost] (docs/theory/history-adjoint.md): J reads the state after step
  /// `step` of this loading program, or (kDissipation) the whole history (study/history.hpp); null:
  /// the static problem. Shared and const: copies of the definition read one program.
  std::shared_ptr<const LoadingProgramDefinition> program;
  /// [cost] step: the 1-based step whose state J reads; 0 = the last step.
  int step = 0;
};

/// [solver] engine settings: which engine solves the state problem (study/state_engine.hpp;
/// docs/petsc-engine.md) and its options.
struct EngineDefinition {
  StateEngine::Kind kind = StateEngine::kDirect;
  /// kPetsc: PETSc options for the Krylov solver (e.g. "-ksp_type gmres -pc_type hypre"); an
  /// option no PETSc object uses is an error at the first solve.
  std::string petsc_options;
  /// kPetsc: ‖F‖ <= relative_tolerance·‖F(u_d)‖ ends the Newton method (in (0, 1)).
  double relative_tolerance = 1e-11;
  /// kPetsc: cap on Newton iterations (>= 1).
  int max_iterations = 60;
};

/// A body brought as a mesh file (docs/meshes.md) instead of the structured grid: the mesh as read
/// (mesh::GmshMesh, no design variables) and how the design moves it (build_mesh.hpp).
struct ImportedMeshDefinition {
  std::filesystem::path file;                   ///< where the mesh came from (for messages)
  std::shared_ptr<const mesh::Mesh> reference;  ///< never null; shared, the mesh is read once
  mesh::DesignMotion motion;                    ///< the design patch, the chart's frame, the extension
  std::vector<std::filesystem::path> sources{};  ///< every file read to make it (the run's fingerprint)
};

struct BodyDefinition {
  std::string name = "body";                 ///< used in output file names
  shape::BezierShape shape = shape::BezierShape::curve(1.0, 2);
  double height = 1.0;                       ///< C4 [m]
  mesh::GridResolution resolution;          ///< of the structured grid that produces the mesh
  /// The boundary set that is Γ_c: the Bézier surface is the grid's "bottom".
  fem::IsotropicMaterial material;
  std::string contact_surface = "bottom";
  std::vector<fem::FaceDirichlet> dirichlet;  ///< Γ_u
  std::vector<fem::FaceTraction> tractions;   ///< Γ_p
  /// Point / node-set forces [N] (docs/experiments.md §3).
  std::vector<fem::NodalForce> forces;
  std::vector<fem::NodalConstraint> constraints;  ///< point / node-set displacements (constant in programs)
  /// Rigid loading plates driven by a total force (docs/theory/loading-plate.md); their forces are
  /// the same in every step of a loading program and every load case.
  std::vector<fem::LoadingPlate> plates;
  shape::AdmissibleSetParameters admissible;  ///< Υ
  Eigen::VectorXd initial_design;             ///< α⁰
  /// [design] friction_orientation (docs/theory/friction-design.md): the orientation φ of the
  /// contact's law is a design variable too, x = (α, s) (study/orientation_design.hpp);
  /// absent: x = α.
  std::optional<OrientationDesignDefinition> friction_orientation;
  std::optional<ContactDefinition> contact;   ///< absent: no foundation (pure elasticity)
  linalg::SpdSolver::Options linear_solver;   ///< the backend that factorizes the stiffness
  EngineDefinition engine;                    ///< [solver] engine (direct or PETSc)
  /// Absent: the structured grid of shape, height and resolution. Present: an imported body;
  /// shape then spans the design patch's chart (mesh::patch_chart) and height is the body's
  /// extent along the foundation normal.
  std::optional<ImportedMeshDefinition> imported_mesh;
};

}  // namespace frictopt::study
