// SPDX-License-Identifier: MIT
// The Hertz block of docs/contact-validation.md (paraboloid R = 2 m on a 1 × 1 × 1 m block, top
// pushed down 12 mm) solved once through study::ShapeOracle (state, then the compliance
// subgradient), with the floor (one Cholesky factorization + solve of the same stiffness matrix
// without contact) measured in the same process. One configuration per process, so that the
// peak RSS is this configuration's. Prints one `key=value` line; bench/contact/run_hertz.sh
// runs the configurations side by side for this build and a previous one.
//
//   hertz_bench CELLS LAYERS GROWTH [MU SHIFT [DENSE_MAX [WIDTH HEIGHT [BOX_LO BOX_HI]]]] [fine_depth=D [vertical_growth=R]]
//
// Without fine_depth the vertical grading is the power law (below); fine_depth=D > 0 selects
// the vertical grading "contact" ([mesh] vertical_grading = "contact"): equal layers down to
// depth D, growing by at most vertical_growth (default 1.2) per layer above. key=value words
// may stand anywhere; the others are positional.
//
// GROWTH = 1: uniform grid; > 1: in-plane grading toward [BOX_LO, BOX_HI]² (default
// [0.3, 0.7]·WIDTH). MU = 0: frictionless; > 0: regular_polygon(MU, 16) and the top also moved
// SHIFT metres along x1 (one static Coulomb step). The vertical grading makes the bottom layer
// as thick as the in-plane cell at the apex (as in tests/study/contact_validation.hpp).
// Sources only the public API that the previous frictopt (966f3ca) already had.
#include <sys/resource.h>
#include <time.h>

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "frictopt/contact/friction_law.hpp"
#include "frictopt/cost/cost_functional.hpp"
#include "frictopt/mesh/graded_coordinates.hpp"
#include "frictopt/study/loading_program.hpp"
#include "frictopt/study/shape_oracle.hpp"
#include "common/timing.hpp"

namespace {

using frictopt::bench::Clock;
using frictopt::bench::seconds;
using frictopt::bench::peak_rss_megabytes;

using namespace frictopt;
// CPU seconds of the whole process (all threads): on a machine shared with other jobs the wall
// clock measures the load as much as the code; with one BLAS thread the CPU time is what an idle
// core would take.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Config {
  int cells = 32, layers = 11;
  double growth = 1.0, mu = 0.0, shift = 0.0;
  int dense_max = 12000;
  double width = 1.0, height = 1.0, box_lo = -1, box_hi = -1;
  double radius = 2.0, young = 1e9, poisson = 0.3, depth = 0.012;
  double fine_depth = 0.0, vertical_growth = 1.2;  // fine_depth > 0: vertical grading "contact"
  bool program = false;  // MU > 0: normal load without friction, then the tangential shift (two steps)
};

double apex_cell(const Config& c) {
  if (c.growth == 1.0) return c.width / c.cells;
  const std::vector<double> x = mesh::graded_coordinates(c.width, c.cells, c.box_lo, c.box_hi, c.growth, "cells");
  double h = c.width;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) h = std::min(h, x[i + 1] - x[i]);
  return h;
}

study::BodyDefinition block(const Config& c) {
  study::BodyDefinition def;
  def.name = "hertz-block";
  def.shape = shape::BezierShape::surface(c.width, c.width, 3, 3);
  def.height = c.height;
  def.resolution.cells = {c.cells, c.cells, c.layers};
  if (c.fine_depth > 0) {
    def.resolution.vertical_grading = mesh::VerticalGrading::kContact;
    def.resolution.fine_depth = c.fine_depth;
    def.resolution.vertical_growth = c.vertical_growth;
  } else {
    def.resolution.grading =
        std::clamp(std::log(c.height / apex_cell(c)) / std::log(static_cast<double>(c.layers)), 1.0, 10.0);
  }
  if (c.growth != 1.0) {
    def.resolution.growth = c.growth;
    def.resolution.refine_box = std::array<double, 4>{c.box_lo, c.box_hi, c.box_lo, c.box_hi};
  }
  def.material.young = c.young;
  def.material.poisson = c.poisson;
  if (c.program) {  // the vertical and the tangential motion of the top, scaled per step
    def.dirichlet.push_back({"top", {2}, Eigen::Vector3d(0.0, 0.0, -c.depth)});
    def.dirichlet.push_back({"top", {0, 1}, Eigen::Vector3d(c.shift, 0.0, 0.0)});
  } else {
    def.dirichlet.push_back({"top", {}, Eigen::Vector3d(c.shift, 0.0, -c.depth)});
  }
  def.admissible.upper_bound = c.height / 2;
  def.admissible.height = c.height;
  // Paraboloid ((x1 − L/2)² + (x2 − L/2)²)/(2R) as a 3 × 3 Bézier net (α_ij = c_i + c_j).
  const double end = c.width * c.width / (8.0 * c.radius);
  const double cc[3] = {end, -end, end};
  def.initial_design.resize(9);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) def.initial_design(i + 3 * j) = cc[i] + cc[j];
  study::ContactDefinition contact;
  contact.law = c.mu > 0 ? contact::FrictionLaw::regular_polygon(c.mu, 16) : contact::FrictionLaw::disc(0.0);
  contact.dense_delassus_max_unknowns = c.dense_max;
  def.contact = contact;
  return def;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s CELLS LAYERS GROWTH [MU SHIFT [DENSE_MAX [WIDTH HEIGHT [BOX_LO BOX_HI]]]]\n", argv[0]);
    return 2;
  }
  Config c;
  std::vector<char*> positional{argv[0]};
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    const auto eq = word.find('=');
    if (eq == std::string::npos) {
      positional.push_back(argv[i]);
    } else if (word.substr(0, eq) == "fine_depth") {
      c.fine_depth = std::atof(word.c_str() + eq + 1);
    } else if (word.substr(0, eq) == "vertical_growth") {
      c.vertical_growth = std::atof(word.c_str() + eq + 1);
    } else if (word.substr(0, eq) == "program") {
      c.program = std::atoi(word.c_str() + eq + 1) != 0;
    } else {
      std::fprintf(stderr, "unknown option %s (expected fine_depth=D, vertical_growth=R or program=1)\n", argv[i]);
      return 2;
    }
  }
  argc = static_cast<int>(positional.size());
  argv = positional.data();
  c.cells = std::atoi(argv[1]);
  c.layers = std::atoi(argv[2]);
  c.growth = std::atof(argv[3]);
  if (argc > 5) { c.mu = std::atof(argv[4]); c.shift = std::atof(argv[5]); }
  if (argc > 6) c.dense_max = std::atoi(argv[6]);
  if (argc > 8) { c.width = std::atof(argv[7]); c.height = std::atof(argv[8]); }
  c.box_lo = argc > 10 ? std::atof(argv[9]) : 0.3 * c.width;
  c.box_hi = argc > 10 ? std::atof(argv[10]) : 0.7 * c.width;
  const study::BodyDefinition definition = block(c);

  // Floor: one factorization (CHOLMOD's own ordering) + one solve, no contact.
  double floor_s = 0, floor_flops = 0;
  const double floor_cpu0 = cpu_seconds();
  {
    study::BodyDefinition plain = definition;
    plain.contact.reset();
    study::ElasticBody elastic(plain);
    const study::BodyState s = elastic.solve(plain.initial_design);
    floor_s = s.summary.factorization_seconds + s.summary.solve_seconds;
    floor_flops = elastic.elasticity().factorization().factor_flops();
  }
  const double floor_cpu_s = cpu_seconds() - floor_cpu0;  // with the assembly (the wall floor_s has none)
  const double floor_rss = peak_rss_megabytes();

  study::ElasticBody body(definition);
  const contact::ContactBoundary& boundary = *body.contact_boundary();
  // What the line reports of the contact solve(s): the state without the assembly, and the
  // normal forces the Hertz estimators read.
  Eigen::VectorXd lambda;
  double factorization_s = 0, state_s = 0, contact_setup_s = 0, coulomb_s = 0, subgradient_s = 0, kkt = 0;
  int fp_its = 0, qp_its = 0, applies = 0;
  bool ok = false;
  std::string delassus, note;
  const double solve_cpu0 = cpu_seconds();
  double state_cpu_s = 0;  // the state (both steps of a program) with its assembly, CPU seconds
  if (c.program) {
    // Normal load without friction (Hertz: the errors are this step's), then friction on and
    // the top moved SHIFT sideways (Cattaneo-Mindlin): one factorization for both steps.
    study::LoadingProgramDefinition program;
    program.steps.push_back({"normal", {}, {1.0, 0.0}, {}, false});
    program.steps.push_back({"tangential", {}, {1.0, 1.0}, {}, true});
    study::LoadingProgram runner(body, program);
    const auto summary = runner.run(definition.initial_design, [&](const study::LoadStepResult& step) {
      if (step.step == 1 && step.state.contact) lambda = step.state.contact->state.normal_forces();
      if (step.state.contact) {
        const auto& r = step.state.contact->summary;
        fp_its += r.iterations;
        qp_its += r.qp_iterations;
        applies += r.operator_applications;
        kkt = std::max(kkt, r.kkt_residual);
        note += (note.empty() ? "" : "|") + r.message;
        if (step.state.contact->delassus) delassus = step.state.contact->delassus->kind();
      }
      state_s += step.state.summary.factorization_seconds + step.state.summary.solve_seconds;
    });
    ok = summary.status == Status::kConverged;
    state_cpu_s = cpu_seconds() - solve_cpu0;
    factorization_s = summary.factorization_seconds;
    coulomb_s = summary.contact_seconds;
    contact_setup_s = state_s - factorization_s - coulomb_s;
    if (!ok) note += "|" + summary.message;
  } else {
    study::ShapeOracle oracle(body, cost::make_compliance());
    const auto t0 = Clock::now();
    const study::Evaluation& e = oracle.evaluate_design(definition.initial_design, false);
    const auto t1 = Clock::now();
    state_cpu_s = cpu_seconds() - solve_cpu0;
    const study::Evaluation& g = oracle.evaluate_design(definition.initial_design, true);
    const auto t2 = Clock::now();
    const study::BodyState& state = oracle.last_state();
    state_s = seconds(t0, t1) - e.state.assembly_seconds;
    lambda = state.contact->state.normal_forces();
    factorization_s = e.state.factorization_seconds;
    contact_setup_s = e.state.solve_seconds - e.contact.time_seconds;
    coulomb_s = e.contact.time_seconds;
    subgradient_s = seconds(t1, t2);
    fp_its = e.contact.iterations;
    qp_its = e.contact.qp_iterations;
    applies = e.contact.operator_applications;
    kkt = e.contact.kkt_residual;
    ok = e.ok && g.ok;
    delassus = state.contact->delassus->kind();
    note = e.contact.message;
  }
  if (lambda.size() == 0) {
    std::fprintf(stderr, "no contact state: %s\n", note.c_str());
    return 3;
  }

  // Hertz: E* = E/(1 − ν²), a = (3PR/(4E*))^{1/3}, p0 = 3P/(2πa²), P the measured load.
  const double load = lambda.sum();
  const double e_star = c.young / (1 - c.poisson * c.poisson);
  const double a_hertz = std::cbrt(3 * load * c.radius / (4 * e_star));
  const double p_hertz = 3 * load / (2 * std::numbers::pi * a_hertz * a_hertz);
  const Eigen::MatrixXd& x = boundary.plane_coordinates();
  const Eigen::VectorXd r = (x.array() - c.width / 2).matrix().rowwise().norm();
  const double a_moment = std::sqrt(2.5 * lambda.dot(r.cwiseAbs2()) / load);
  // Lumped tributary areas of the (tensor-product) bottom grid: the product of the half
  // spacings to the neighbours in x1 and x2 (the bottom nodes lie on the grid's column lines).
  std::vector<double> xs(static_cast<std::size_t>(x.rows()));
  for (Eigen::Index i = 0; i < x.rows(); ++i) xs[static_cast<std::size_t>(i)] = x(i, 0);
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end(), [](double a, double b) { return std::abs(a - b) < 1e-12; }), xs.end());
  const auto half_span = [&](double v) {
    const auto it = std::lower_bound(xs.begin(), xs.end(), v - 1e-12);
    const std::size_t k = static_cast<std::size_t>(it - xs.begin());
    const double left = k > 0 ? xs[k] - xs[k - 1] : 0.0;
    const double right = k + 1 < xs.size() ? xs[k + 1] - xs[k] : 0.0;
    return 0.5 * (left + right);
  };
  Eigen::Index apex = 0;
  r.minCoeff(&apex);
  const double p_apex = lambda(apex) / (half_span(x(apex, 0)) * half_span(x(apex, 1)));
  // Profile fit p_i² = p0² − (p0²/a²) r_i² over the loaded nodes with r < 0.8·a_moment.
  double s0 = 0, s1 = 0, s2 = 0, u0 = 0, u1 = 0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    if (lambda(i) <= 0 || r(i) >= 0.8 * a_moment) continue;
    const double p = lambda(i) / (half_span(x(i, 0)) * half_span(x(i, 1)));
    const double xx = r(i) * r(i), yy = p * p;
    s0 += 1; s1 += xx; s2 += xx * xx; u0 += yy; u1 += xx * yy;
  }
  const double det = s0 * s2 - s1 * s1;
  const double intercept = (s2 * u0 - s1 * u1) / det, slope = (s0 * u1 - s1 * u0) / det;
  const double a_fit = std::sqrt(-intercept / slope), p_fit = std::sqrt(intercept);
  // The thinnest layer of the grid at the apex column (the bottom of the paraboloid is at 0).
  double thinnest_layer = c.height;
  {
    const std::vector<double> z =
        c.fine_depth > 0 ? mesh::contact_layer_coordinates(c.height, c.layers, c.fine_depth, c.vertical_growth)
                         : std::vector<double>{0.0, c.height * std::pow(1.0 / c.layers, definition.resolution.grading)};
    for (std::size_t k = 0; k + 1 < z.size(); ++k) thinnest_layer = std::min(thinnest_layer, z[k + 1] - z[k]);
  }
  int loaded = 0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) loaded += lambda(i) > 0;

  std::printf(
      "cells=%d layers=%d growth=%g fine_depth=%g vertical_growth=%g thinnest_layer=%.5f mu=%g program=%d width=%g "
      "unknowns=%d contact_unknowns=%lld loaded_nodes=%d "
      "delassus=%s floor_s=%.3f factorization_s=%.3f state_s=%.3f contact_setup_s=%.3f coulomb_s=%.3f "
      "subgradient_s=%.3f state_over_floor=%.3f state_over_factorization=%.3f subgradient_over_state=%.3f "
      "fp_its=%d qp_its=%d applies=%d kkt=%.2e ok=%d P=%.6e a_fit_err=%+.4f%% a_moment_err=%+.4f%% "
      "p_apex_err=%+.4f%% p_fit_err=%+.4f%% h_apex=%.5f floor_rss_MB=%.0f peak_rss_MB=%.0f floor_flops=%.3e "
      "factor_flops=%.3e floor_cpu_s=%.3f state_cpu_s=%.3f ",
      c.cells, c.layers, c.growth, c.fine_depth, c.vertical_growth, thinnest_layer, c.mu, c.program ? 1 : 0, c.width,
      body.elasticity().dofs().num_free(), static_cast<long long>(boundary.num_unknowns()), loaded, delassus.c_str(),
      floor_s, factorization_s, state_s, contact_setup_s, coulomb_s, subgradient_s, state_s / floor_s,
      state_s / factorization_s, subgradient_s / state_s, fp_its, qp_its, applies, kkt, ok ? 1 : 0, load,
      100 * (a_fit / a_hertz - 1), 100 * (a_moment / a_hertz - 1), 100 * (p_apex / p_hertz - 1),
      100 * (p_fit / p_hertz - 1), apex_cell(c), floor_rss, peak_rss_megabytes(), floor_flops,
      body.elasticity().factorization().factor_flops(), floor_cpu_s, state_cpu_s);
  // The Coulomb solver's own report (one word: the table script ignores it).
  std::replace(note.begin(), note.end(), ' ', '_');
  std::printf("note=%s\n", note.c_str());
  return ok ? 0 : 3;
}
