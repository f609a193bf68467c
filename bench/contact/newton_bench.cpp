// SPDX-License-Identifier: MIT
// The Coulomb state of a slip-heavy box by the fixed point, the semismooth Newton method and the
// automatic choice (docs/contact.md, "Semismooth Newton"): state time over factorization time,
// CPU seconds, iterations, the load average, and the agreement of the solutions.
//
//   newton_bench [NX NY NZ [SHIFT [PRESS [LAW [METHODS [GRADING [BOTTOM [POISSON [BUDGET]]]]]]]]]
//
// defaults 32 32 8, SHIFT 4e-4 m, PRESS 2e-4 m, LAW disc (disc | polygon4 | ellipse), METHODS
// fixed_point,semismooth_newton,automatic, GRADING 1 (the vertical power-law grading toward the
// contact surface, [mesh] grading), BOTTOM flat (flat | dish: the dish-shaped 3 × 3 Bézier
// bottom of the sensitivity tests, heights 0.4–1.7 mm, so the pressure varies), POISSON 0.33
// (a rubber-like pad: 0.45–0.49, which couples normal and tangential response strongly; LAW
// disc:MU for another μ), BUDGET 0.1 (the automatic handover's products with M per contact
// unknown, NewtonOptions::automatic_applications_per_unknown). The body: a 1 m × 1 m × 0.25 m aluminium block with a
// flat bottom (every bottom node touches), its top moved PRESS down and SHIFT sideways, μ = 0.3
// (polygon4: the anisotropic 4-gon 0.4/0.2; ellipse: 0.3/0.2): most contact nodes slip.
#include <fmt/format.h>

#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/timing.hpp"
#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace {

using namespace frictopt;

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one;
  in >> one;
  return one.empty() ? "?" : one;
}

contact::FrictionLaw law_named(const std::string& name) {
  if (name.rfind("disc:", 0) == 0) return contact::FrictionLaw::disc(std::atof(name.c_str() + 5));
  if (name == "polygon4") return contact::FrictionLaw::polygon({0.4, 0.2, 0.4, 0.2});
  if (name == "ellipse") return contact::FrictionLaw::ellipse(0.3, 0.2);
  return contact::FrictionLaw::disc(0.3);
}

study::BodyDefinition slip_box(int nx, int ny, int nz, double grading, bool dish, double poisson, double shift,
                               double press, const contact::FrictionLaw& law, contact::CoulombMethod method,
                               double budget) {
  study::BodyDefinition b;
  b.shape = shape::BezierShape::surface(1.0, 1.0, 3, 3);
  b.height = 0.25;
  b.resolution = {{nx, ny, nz}, grading};
  b.material = {7e10, poisson, fem::PlaneModel::kPlaneStrain};
  b.dirichlet = {{"top", {}, Eigen::Vector3d(shift, 0.0, -press)}};
  b.admissible.upper_bound = 5e-3;
  b.admissible.height = 0.25;
  b.initial_design = Eigen::VectorXd::Zero(9);
  if (dish) b.initial_design << 1.4e-3, 1.0e-3, 1.5e-3, 0.9e-3, 0.4e-3, 1.1e-3, 1.6e-3, 1.2e-3, 1.7e-3;
  study::ContactDefinition c;
  c.law = law;
  c.coulomb.method = method;
  c.coulomb.newton.automatic_applications_per_unknown = budget;
  b.contact = c;
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  const int nx = argc > 1 ? std::atoi(argv[1]) : 32, ny = argc > 2 ? std::atoi(argv[2]) : 32,
            nz = argc > 3 ? std::atoi(argv[3]) : 8;
  const double shift = argc > 4 ? std::atof(argv[4]) : 4e-4, press = argc > 5 ? std::atof(argv[5]) : 2e-4;
  const std::string law_name = argc > 6 ? argv[6] : "disc";
  std::vector<std::string> methods{"fixed_point", "semismooth_newton", "automatic"};
  if (argc > 7) {
    methods.clear();
    std::stringstream list(argv[7]);
    for (std::string m; std::getline(list, m, ',');) methods.push_back(m);
  }
  const double grading = argc > 8 ? std::atof(argv[8]) : 1.0;
  const bool dish = argc > 9 && std::string(argv[9]) == "dish";
  const double poisson = argc > 10 ? std::atof(argv[10]) : 0.33;
  const double budget = argc > 11 ? std::atof(argv[11]) : 0.1;
  const contact::FrictionLaw law = law_named(law_name);
  fmt::print("| grid | law | method | used | contact unknowns | stick / slip / sep. | factorization [s] | contact solve [s] | "
             "state [s] | state / factorization | state CPU [s] | iterations (FP / Newton / linear / LU) | max |Δz|/|z| | "
             "load avg |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  Eigen::VectorXd first;
  for (const std::string& name : methods) {
    const contact::CoulombMethod method = contact::parse_coulomb_method(name);
    study::ElasticBody body(slip_box(nx, ny, nz, grading, dish, poisson, shift, press, law, method, budget));
    const std::string load_before = load_average();
    const double cpu0 = cpu_seconds();
    const study::BodyState state = body.solve(body.definition().initial_design, "bench");
    const double cpu = cpu_seconds() - cpu0;
    if (!state.contact) return 1;
    const auto& r = state.contact->summary;
    const auto& z = state.contact->state.z;
    double diff = 0.0;
    if (first.size() == 0)
      first = z;
    else
      diff = (z - first).cwiseAbs().maxCoeff() / first.cwiseAbs().maxCoeff();
    const auto& res = state.contact->resultants;
    const double fact = state.summary.factorization_seconds;
    const double total = fact + state.summary.solve_seconds;
    const std::string label = name == "automatic" && budget != 0.1 ? fmt::format("automatic (m·{:g})", budget) : name;
    fmt::print("| {}×{}×{}{} | {} | {} | {} | {} | {} / {} / {} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {} / {} / {} / {} | "
               "{:.1e} | {}–{} |\n",
               nx, ny, nz, (grading != 1.0 ? fmt::format(" graded {:g}", grading) : std::string()) + (dish ? " dish" : "") + (poisson != 0.33 ? fmt::format(" ν {:g}", poisson) : std::string()), law_name, label, contact::to_string(r.method_used), z.size(), res.num_stick, res.num_slip,
               res.num_separated, fact, r.time_seconds, total, total / fact, cpu, r.iterations, r.newton_iterations,
               r.linear_iterations, r.factorizations, diff, load_before, load_average());
    fmt::print(stderr, "{}: {}\n  {}\n", name, r.brief_report(), r.message);
    if (!r.converged()) return 3;
  }
  return 0;
}
