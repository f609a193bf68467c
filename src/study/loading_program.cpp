// SPDX-License-Identifier: MIT
#include "frictopt/study/loading_program.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <string_view>

#include "frictopt/core/error.hpp"
#include "frictopt/fem/node_selection.hpp"

namespace frictopt::study {
namespace {

void check_scales(const std::vector<double>& scales, std::size_t expected, std::string_view where, std::size_t step,
                  const char* field, const char* table) {
  if (scales.empty()) return;
  if (scales.size() != expected)
    throw InvalidInput(
        fmt::format("{}.step[{}].{} has {} entries, but the case has {} [[{}]] table{}; "
                    "expected one scale per [[{}]] (or none, to keep the previous step's)",
                    where, step, field, scales.size(), expected, table, expected == 1 ? "" : "s", table));
  for (std::size_t j = 0; j < scales.size(); ++j)
    if (!std::isfinite(scales[j]))
      throw InvalidInput(fmt::format("{}.step[{}].{}[{}] = {}; expected a finite number", where, step,
                                     field, j, scales[j]));
}

}  // namespace

StepLoadBuilder::StepLoadBuilder(const ElasticBody& body,
                                 const Eigen::Ref<const Eigen::MatrixXd>& X)
    : body_(body), X_(X) {
  const BodyDefinition& def = body.definition();
  for (const fem::FaceTraction& t : def.tractions)
    traction_loads_.push_back(fem::face_traction_load(body.mesh(), X_, t));
  for (const fem::NodalForce& f : def.forces)
    force_loads_.push_back(fem::nodal_force_load(body.mesh(), body.elasticity().dofs(), {f}));
  case_prescribed_ = fem::expand_dirichlet(body.mesh(), def.dirichlet);
}

Eigen::VectorXd StepLoadBuilder::applied(const std::vector<double>& load_scale,
                                         const std::vector<double>& force_scale) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(body_.mesh().num_dofs());
  for (std::size_t j = 0; j < traction_loads_.size(); ++j)
    f += load_scale.at(j) * traction_loads_[j];
  for (std::size_t j = 0; j < force_loads_.size(); ++j) f += force_scale.at(j) * force_loads_[j];
  return f;
}

StepLoads StepLoadBuilder::build(const std::vector<double>& load_scale,
                                 const std::vector<double>& force_scale,
                                 const std::vector<fem::FaceDirichlet>& dirichlet,
                                 const Eigen::VectorXd& previous_tangential, bool friction) const {
  const mesh::Mesh& mesh = body_.mesh();
  const fem::LinearElasticity& fem = body_.elasticity();
  FRICTOPT_ASSERT(
      load_scale.size() == traction_loads_.size() && force_scale.size() == force_loads_.size(),
      "StepLoadBuilder::build: one scale per load");
  // l^k − l: each load enters with (scale − 1), so a step at the case's own scales adds exact
  // zeros and reproduces the static solve bit for bit.
  Eigen::VectorXd change = Eigen::VectorXd::Zero(mesh.num_dofs());
  for (std::size_t j = 0; j < traction_loads_.size(); ++j)
    if (load_scale[j] != 1.0) change += (load_scale[j] - 1.0) * traction_loads_[j];
  for (std::size_t j = 0; j < force_loads_.size(); ++j)
    if (force_scale[j] != 1.0) change += (force_scale[j] - 1.0) * force_loads_[j];
  const fem::PrescribedDofs prescribed = fem::expand_dirichlet(mesh, dirichlet);
  if (prescribed.dofs != case_prescribed_.dofs)
    throw InvalidInput(
        "StepLoadBuilder: the step's Dirichlet conditions prescribe other DOFs than the body's; "
        "expected the same faces and components with other values (one factorization)");
  StepLoads step;
  step.prescribed_change = Eigen::VectorXd::Zero(mesh.num_dofs());
  for (std::size_t d = 0; d < prescribed.dofs.size(); ++d)
    step.prescribed_change(prescribed.dofs[d]) = prescribed.values[d] - case_prescribed_.values[d];
  step.load_change = fem.dofs().restrict_forces(change);
  if (!step.prescribed_change.isZero(0.0)) {
    // Lifting of the change of prescribed values: −A_fd Δu_d, with A_full Δu_d from the
    // element-by-element residual (A_full u − l_traction) + l_traction.
    const Eigen::VectorXd lifted = fem.residual(X_, step.prescribed_change) + fem.traction_load(X_);
    step.load_change -= fem.dofs().restrict_forces(lifted);
  }
  step.previous_tangential = previous_tangential;
  step.friction = friction;
  step.applied_change = std::move(change);
  return step;
}

Eigen::VectorXd StepLoadBuilder::tangential_displacement(
    const Eigen::VectorXd& displacement) const {
  const contact::ContactBoundary* boundary = body_.contact_boundary();
  return boundary ? boundary->tangential_displacements(displacement) : Eigen::VectorXd();  // in the foundation's frame
}

std::string step_tables(std::string_view where) {
  return where.starts_with("load_case") ? "[[load_case.step]]" : "[[program.step]]";
}

void LoadingProgramDefinition::validate(const BodyDefinition& body, std::string_view where) const {
  if (steps.empty())
    throw InvalidInput(fmt::format("{}.step: the program has no steps; expected at least one {} table", where,
                                   step_tables(where)));
  if (steps.size() > kMaxProgramSteps)
    throw InvalidInput(fmt::format("{}.step: the program has {} steps; expected at most {} {} tables (each is a "
                                   "contact solve; docs/case-format.md, \"Size limits\")",
                                   where, steps.size(), kMaxProgramSteps, step_tables(where)));
  for (std::size_t k = 0; k < steps.size(); ++k) {
    check_scales(steps[k].load_scale, body.tractions.size(), where, k, "load_scale", "load");
    check_scales(steps[k].dirichlet_scale, body.dirichlet.size(), where, k, "dirichlet_scale", "dirichlet");
    check_scales(steps[k].force_scale, body.forces.size(), where, k, "force_scale", "force");
  }
}

std::vector<LoadStepDefinition> LoadingProgramDefinition::scales_in_force(const BodyDefinition& body) const {
  std::vector<double> load(body.tractions.size(), 1.0), dirichlet(body.dirichlet.size(), 1.0),
      force(body.forces.size(), 1.0);
  std::vector<LoadStepDefinition> out = steps;
  for (LoadStepDefinition& s : out) {
    if (!s.load_scale.empty()) load = s.load_scale;
    if (!s.dirichlet_scale.empty()) dirichlet = s.dirichlet_scale;
    if (!s.force_scale.empty()) force = s.force_scale;
    s.load_scale = load;
    s.dirichlet_scale = dirichlet;
    s.force_scale = force;
  }
  return out;
}

std::string LoadingProgram::Summary::brief_report() const {
  return fmt::format(
      "loading program: {} ({}); {} steps solved, {} factorization{} ({:.3f} s), contact {:.3f} s, "
      "total {:.3f} s",
      to_string(status), message, steps_solved, factorizations, factorizations == 1 ? "" : "s",
      factorization_seconds, contact_seconds, time_seconds);
}

LoadingProgram::LoadingProgram(ElasticBody& body, LoadingProgramDefinition program)
    : body_(body), program_(std::move(program)) {
  program_.validate(body_.definition());
}

LoadingProgram::Summary LoadingProgram::run(const Eigen::Ref<const Eigen::VectorXd>& alpha,
                                            const StepCallback& on_step) {
  const auto start = std::chrono::steady_clock::now();
  const BodyDefinition& def = body_.definition();
  const mesh::Mesh& mesh = body_.mesh();
  const int dim = mesh.dim();
  if (alpha.size() != def.shape.num_controls())
    throw InvalidInput(fmt::format("design: has {} control heights; expected {}", alpha.size(),
                                   def.shape.num_controls()));
  const StepLoadBuilder builder(body_, mesh.positions(alpha));
  const contact::ContactBoundary* boundary = body_.contact_boundary();
  const Eigen::Index p = boundary ? boundary->num_nodes() : 0;
  body_.set_warm_start(std::nullopt);  // u⁰ = 0: the program starts from the unloaded body
  Eigen::VectorXd previous_tangential = Eigen::VectorXd::Zero((dim - 1) * p);

  const std::vector<LoadStepDefinition> in_force = program_.scales_in_force(def);
  Summary summary;
  summary.status = Status::kConverged;
  for (std::size_t k = 0; k < program_.steps.size(); ++k) {
    const LoadStepDefinition& sd = program_.steps[k];
    const std::vector<double>& ls = in_force[k].load_scale;
    const std::vector<double>& ds = in_force[k].dirichlet_scale;
    const std::vector<double>& fs = in_force[k].force_scale;
    std::vector<fem::FaceDirichlet> scaled = def.dirichlet;
    for (std::size_t j = 0; j < scaled.size(); ++j) scaled[j].displacement *= ds[j];
    const StepLoads step = builder.build(ls, fs, scaled, previous_tangential, sd.friction);

    LoadStepResult result;
    result.step = static_cast<int>(k) + 1;
    result.label = sd.label.empty() ? fmt::format("step {}", k + 1) : sd.label;
    result.state = body_.solve_step(alpha, step, result.label);
    if (result.state.summary.factorization_seconds > 0.0) ++summary.factorizations;
    summary.factorization_seconds += result.state.summary.factorization_seconds;
    if (result.state.contact) summary.contact_seconds += result.state.contact->summary.time_seconds;
    result.external_work = builder.applied(ls, fs).dot(result.state.displacement);
    result.tangential_displacement = builder.tangential_displacement(result.state.displacement);
    const bool ok = result.state.summary.status == Status::kConverged;
    if (on_step) on_step(result);
    if (!ok) {
      summary.status = result.state.summary.status;
      summary.message = fmt::format("{}: {}", result.label, result.state.summary.message);
      break;
    }
    ++summary.steps_solved;
    previous_tangential = result.tangential_displacement;
  }
  if (summary.status == Status::kConverged)
    summary.message = fmt::format("all {} steps solved on one factorization", summary.steps_solved);
  summary.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace frictopt::study
