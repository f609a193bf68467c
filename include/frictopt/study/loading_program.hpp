// SPDX-License-Identifier: MIT
// Quasi-static loading programs (docs/theory/loading-program.md):
// a sequence of load steps on one body at one design, each step scaling the case's tractions,
// point forces and prescribed displacements; Coulomb friction acts on the slip increment since
// the previous step and the contact state carries over. The stiffness is the same in every
// step, so one factorization (and one Delassus matrix) serves the whole program.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "frictopt/core/status.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/loading_program_definition.hpp"

namespace frictopt::study {

/// The result of one step.
struct LoadStepResult {
  int step = 0;  ///< 1-based
  std::string label;
  BodyState state;  ///< the body after the step; contact u_t = the step's slip increment
  double external_work = kNaN;  ///< (tractions + point forces of the step)ᵀ u [J]
  /// Tangential displacement of the contact nodes after the step ((dim−1)·p): the slip
  /// reference of the next step.
  Eigen::VectorXd tangential_displacement;
};

/// Builds the StepLoads of ElasticBody::solve_step from a step's scales and Dirichlet values, at
/// one design (positions X). Keeps the load vector of each [[load]] and [[force]] separately.
/// `body` must outlive the builder.
class StepLoadBuilder {
 public:
  StepLoadBuilder(const ElasticBody& body, const Eigen::Ref<const Eigen::MatrixXd>& X);
  /// `load_scale`, `force_scale`: one entry per traction / force of the body. `dirichlet`: the
  /// step's conditions, which must prescribe exactly the DOFs of the body's (the stiffness and
  /// its factorization stay valid); throws InvalidInput otherwise.
  [[nodiscard]] StepLoads build(const std::vector<double>& load_scale,
                                const std::vector<double>& force_scale,
                                const std::vector<fem::FaceDirichlet>& dirichlet,
                                const Eigen::VectorXd& previous_tangential, bool friction) const;
  /// The step's applied forces (tractions + point forces), full DOF vector, for its work.
  [[nodiscard]] Eigen::VectorXd applied(const std::vector<double>& load_scale,
                                        const std::vector<double>& force_scale) const;
  /// u_t of the contact nodes ((dim−1)·p, node-interleaved) in a full displacement.
  [[nodiscard]] Eigen::VectorXd tangential_displacement(const Eigen::VectorXd& displacement) const;

 private:
  const ElasticBody& body_;
  Eigen::MatrixXd X_;
  std::vector<Eigen::VectorXd> traction_loads_, force_loads_;
  fem::PrescribedDofs case_prescribed_;
};

/// Runs a program on an ElasticBody. `body` must outlive the runner.
class LoadingProgram {
 public:
  struct Summary {
    Status status = Status::kNotRun;
    std::string message = "run() has not been called";
    int steps_solved = 0;    ///< steps whose state converged
    int factorizations = 0;  ///< numeric factorizations of A (1 for a whole program)
    double factorization_seconds = 0.0;
    double contact_seconds = 0.0;  ///< Coulomb solves, summed over the steps
    double time_seconds = 0.0;
    std::string brief_report() const;
  };
  /// Called after each step (also a failed one, which ends the run).
  using StepCallback = std::function<void(const LoadStepResult&)>;

  /// Validates the program against the body's definition (throws InvalidInput).
  LoadingProgram(ElasticBody& body, LoadingProgramDefinition program);

  /// Solves the steps in order at design α, from the unloaded body (u⁰ = 0, no contact
  /// forces). Stops at the first step whose state does not converge (its status is the run's).
  [[nodiscard]] Summary run(const Eigen::Ref<const Eigen::VectorXd>& alpha,
                            const StepCallback& on_step = {});

  const LoadingProgramDefinition& program() const { return program_; }

 private:
  ElasticBody& body_;
  LoadingProgramDefinition program_;
};

}  // namespace frictopt::study
