// SPDX-License-Identifier: MIT
#include "frictopt/study/cost_factory.hpp"

#include <cmath>
#include <optional>
#include <string>

#include "frictopt/core/error.hpp"

namespace frictopt::study {

bool needs_initial_state(const CostDefinition& definition) {
  return (definition.kind == cost::CostKind::kTargetPressure && std::isnan(definition.target_pressure)) ||
         (definition.kind == cost::CostKind::kTractionUniformity && definition.target_traction_initial_mean);
}

std::unique_ptr<cost::CostFunctional> make_cost(const CostDefinition& definition, ElasticBody& body,
                                                const BodyState* initial_state) {
  using Kind = cost::CostKind;
  // The state at α⁰ for "initial_mean" targets: the caller's, or solved here.
  std::optional<BodyState> solved;
  const auto initial = [&](const char* what) -> const BodyState& {
    if (!initial_state) solved = body.solve(body.initial_design(), "initial design");
    const BodyState& s = initial_state ? *initial_state : *solved;
    if (s.summary.status != Status::kConverged)
      throw NumericalFailure(std::string("cost ") + what + " = initial_mean: the state at the initial design did not solve: " +
                             s.summary.message);
    return s;
  };
  switch (definition.kind) {
    case Kind::kTargetPressure: {
      if (!body.contact_boundary()) throw InvalidInput("cost target_pressure needs a body in contact");
      const Eigen::VectorXd& areas = body.contact_boundary()->tributary_areas();
      double pressure = definition.target_pressure;
      if (std::isnan(pressure)) {
        const BodyState& s = initial("target_pressure");
        pressure = s.contact->state.normal_forces().sum() / areas.sum();
      }
      return cost::make_target_normal_force(pressure * areas);
    }
    case Kind::kNormalForcePower: return cost::make_normal_force_power(definition.exponent);
    case Kind::kCompliance: return cost::make_compliance();
    case Kind::kPressureNorm: return cost::make_pressure_norm(definition.exponent);
    case Kind::kTotalSlip: return cost::make_total_slip(definition.smoothing);
    case Kind::kTractionUniformity: {
      if (!definition.target_traction_initial_mean) return cost::make_traction_uniformity(definition.target_traction);
      if (!body.contact_boundary()) throw InvalidInput("cost traction_uniformity needs a body in contact");
      const contact::ContactState& cs = initial("traction_uniformity target").contact->state;
      const int nt = cs.dim - 1;
      Eigen::VectorXd mean = Eigen::VectorXd::Zero(nt);
      for (Eigen::Index i = 0; i < cs.num_nodes(); ++i)
        for (int c = 0; c < nt; ++c) mean(c) -= cs.z(cs.dim * i + c);  // τ_i = −q_i
      return cost::make_traction_uniformity(mean / body.contact_boundary()->tributary_areas().sum());
    }
    case Kind::kDissipation:
      throw InvalidInput("cost.kind = \"dissipation\" reads the history of a loading program: a history cost on a "
                         "one-step case; expected [[program.step]] tables (study::ProgramHistory evaluates it)");
  }
  return nullptr;
}

}  // namespace frictopt::study
