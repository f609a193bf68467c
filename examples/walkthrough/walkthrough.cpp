// SPDX-License-Identifier: MIT
// A walk through frictopt's C++ API, from a body definition to a certified optimal shape:
//
//   BodyDefinition ──► ElasticBody ──► ShapeOracle Θ(α) ──► bundle trust ──► certificate
//
// The body is an aluminium block whose bottom is a 3 × 3 Bézier surface (9 design heights α),
// pressed and dragged onto the rigid foundation x3 <= 0 by a plate glued to its top, with
// anisotropic Coulomb friction (the 4-gon of the thesis' remark 6.2.1). The cost asks for a
// uniform contact pressure (thesis ex. 5.2.1's J1). The same study written as a case file is
// cases3d/punch-anisotropic; docs/architecture.md explains the layers used here.
//
// Build against an installed frictopt (examples/walkthrough/CMakeLists.txt):
//   cmake -S examples/walkthrough -B build-walk -DCMAKE_PREFIX_PATH=<prefix> && cmake --build build-walk
#include <cstdio>

#include "frictopt/contact/friction_law.hpp"
#include "frictopt/study/body_definition.hpp"
#include "frictopt/study/certificate.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/shape_optimization.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace fs = frictopt::study;

int main() {
  // 1. The definition: what a case file holds, as the numeric modules' own types.
  fs::BodyDefinition definition;
  definition.name = "walkthrough";
  definition.shape = frictopt::shape::BezierShape::surface(1.0, 1.0, 3, 3);  // a × b, 3 × 3 net
  definition.height = 0.5;                                                 // m
  definition.resolution = {{8, 8, 4}, 1.0};                                // cells, grading
  definition.material = {7e10, 0.33, frictopt::fem::PlaneModel::kPlaneStrain};  // E [Pa], ν
  // Γ_u: the plate on the top moves 1.2 mm down and 0.1 mm along x1.
  definition.dirichlet = {{"top", {}, Eigen::Vector3d(1e-4, 0.0, -1.2e-3)}};
  // Υ: heights in [0, C0], volume fixed by the initial design (a shallow dish, mean 1 mm).
  definition.admissible.upper_bound = 5e-3;
  definition.admissible.height = 0.5;
  definition.initial_design.resize(9);
  definition.initial_design << 1.5e-3, 1.0e-3, 1.5e-3, 1.0e-3, 0.5e-3, 1.0e-3, 1.5e-3, 1.0e-3, 1.5e-3;
  definition.admissible.volume = 0.5 - definition.initial_design.mean();
  // Friction: per-vertex coefficients μ1 = 0.4 (45°, 225°) and μ2 = 0.2 (135°, 315°).
  fs::ContactDefinition contact;
  contact.law = frictopt::contact::FrictionLaw::polygon({0.4, 0.2, 0.4, 0.2});
  definition.contact = contact;

  // 2. The body: mesh, FE pattern and symbolic factorization, built once; solve(α) gives the state.
  fs::ElasticBody body(definition);
  const auto initial = body.solve(definition.initial_design);
  std::printf("state at alpha0: %s; normal force %.4e N\n", initial.summary.brief_report().c_str(),
              initial.contact->resultants.normal_force);

  // 3. The oracle Θ(α) = J(α, u(α), λ(α)) with one Clarke subgradient per design (one adjoint).
  fs::CostDefinition cost;
  cost.kind = frictopt::cost::CostKind::kTargetPressure;  // λ̄ = the initial mean pressure
  fs::ShapeOracle oracle(body, cost);

  // 4. The bundle trust method over Υ, with the study defaults (ε relative to |Θ(α⁰)|).
  auto options = fs::default_study_options(definition);
  options.epsilon = 1e-4;
  options.max_iterations = 100;
  const auto on_progress = [](const fs::OptimizationProgress& p) {
    if (p.method.iteration % 10 == 0) {
      std::printf("iteration %3d  Theta = %.6e\n", p.method.iteration, p.method.f);
    }
    return frictopt::CallbackResult::kContinue;
  };
  const auto run = fs::optimize(oracle, options, on_progress);
  std::printf("optimize: %s\n", run.message.c_str());

  // 5. The certificate at the final design: index sets, |L|, Clarke distance, (MF1') rank.
  const fs::Certificate certificate = fs::certify(oracle, run.x);
  std::printf("%s\n", certificate.report().c_str());

  // A certified stationary design with a much lower cost than the start.
  const double theta0 = oracle.evaluate_design(definition.initial_design, false).value;
  const bool ok = run.f < 0.5 * theta0 && certificate.clarke_stationary;
  std::printf("Theta: %.6e -> %.6e; %s\n", theta0, run.f, ok ? "certified" : "NOT certified");
  return ok ? 0 : 1;
}
