// SPDX-License-Identifier: MIT
// Shared set-up of the physical validation tests of the contact solver
// (docs/contact-validation.md): blocks with a parabolic (2D) or paraboloidal (3D) Bézier bottom
// pressed on the rigid foundation, nodal pressures, the estimators of contact and stick radii, and
// residual checks.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "frictopt/contact/contact_state.hpp"
#include "frictopt/contact/delassus.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/mesh/graded_coordinates.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::study::validation {

/// One block: width L (3D: L × L), height H, bottom (x'−c)²/(2R) summed over the in-plane axes
/// (apex at the centre c of the base), clamped top moved by `top_displacement`.
struct BlockSpec {
  int dim = 3;
  double width = 1.0;   ///< L [m]
  double height = 1.0;  ///< H [m]
  double radius = 2.0;  ///< R [m] (radius of curvature at the apex)
  int cells = 16;       ///< in-plane cells per direction
  int layers = 8;       ///< vertical cells
  double young = 1.0e9;
  double poisson = 0.3;
  Eigen::VectorXd top_displacement;  ///< size dim: the clamped top's motion (last = vertical)
  contact::FrictionLaw law = contact::FrictionLaw::disc(0.0);
  contact::CoulombMethod method = contact::CoulombMethod::kFixedPoint;
  int dense_max_unknowns = 1500;
  /// In-plane grading (docs/contact-validation.md §1b): growth > 1 grades the columns toward the
  /// square [refine_min, refine_max]² around the apex; 1 keeps the uniform grid.
  double growth = 1.0;
  double refine_min = 0.0, refine_max = 0.0;  ///< [m], both in-plane directions
  /// Vertical grading "contact" (docs/contact-validation.md §1c) when fine_depth > 0: equal layers
  /// down to fine_depth, growing by <= vertical_growth above; otherwise the power law of
  /// bottom_grading.
  double fine_depth = 0.0, vertical_growth = 1.2;
  /// The grid's cells: Q1, or split into P1 simplices ([mesh] element = "tet4"/"tri3").
  mesh::ElementFamily family = mesh::ElementFamily::kTensorProduct;
};

/// The in-plane cell size at the apex: L/cells, or the refinement box's cell when graded.
inline double apex_cell(const BlockSpec& s) {
  if (s.growth == 1.0) return s.width / s.cells;
  const std::vector<double> x =
      mesh::graded_coordinates(s.width, s.cells, s.refine_min, s.refine_max, s.growth, "BlockSpec.cells");
  double h = s.width;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) h = std::min(h, x[i + 1] - x[i]);
  return h;
}

/// Control heights of the 1D quadratic (x − L/2)²/(2R) on [0, L]: Bernstein coefficients of a
/// quadratic with values f(0), f(L/2), f(L) are f(0), 2f(L/2) − (f(0)+f(L))/2, f(L).
inline std::array<double, 3> parabola_controls(double width, double radius) {
  const double end = width * width / (8.0 * radius);
  return {end, 0.0 - end, end};
}

/// The design α of the bottom: 2D the three parabola controls; 3D the tensor net of the sum of
/// the two separable parabolas, α_ij = c_i + c_j (Bernstein bases sum to one).
inline Eigen::VectorXd paraboloid_design(const BlockSpec& s) {
  const auto c = parabola_controls(s.width, s.radius);
  if (s.dim == 2) return Eigen::Vector3d(c[0], c[1], c[2]);
  Eigen::VectorXd alpha(9);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) alpha(i + 3 * j) = c[static_cast<std::size_t>(i)] + c[static_cast<std::size_t>(j)];
  return alpha;
}

/// Vertical grading that makes the bottom layer about as thick as an in-plane cell at the apex:
/// H/layers^g = h (h = L/cells on the uniform grid), clipped to the mesh's range [1, 10].
inline double bottom_grading(const BlockSpec& s) {
  const double g = s.growth == 1.0 ? std::log(s.height * s.cells / s.width) / std::log(static_cast<double>(s.layers))
                                   : std::log(s.height / apex_cell(s)) / std::log(static_cast<double>(s.layers));
  return std::clamp(g, 1.0, 10.0);
}

inline BodyDefinition block_definition(const BlockSpec& s) {
  BodyDefinition def;
  def.name = "validation-block";
  def.shape = s.dim == 2 ? shape::BezierShape::curve(s.width, 3) : shape::BezierShape::surface(s.width, s.width, 3, 3);
  def.height = s.height;
  def.resolution.cells = {s.cells, s.dim == 2 ? 1 : s.cells, s.layers};
  def.resolution.element_family = s.family;
  if (s.fine_depth > 0) {
    def.resolution.vertical_grading = mesh::VerticalGrading::kContact;
    def.resolution.fine_depth = s.fine_depth;
    def.resolution.vertical_growth = s.vertical_growth;
  } else {
    def.resolution.grading = bottom_grading(s);
  }
  if (s.growth != 1.0) {
    def.resolution.growth = s.growth;
    def.resolution.refine_box = std::array<double, 4>{s.refine_min, s.refine_max, s.refine_min, s.refine_max};
  }
  def.material.young = s.young;
  def.material.poisson = s.poisson;
  def.material.plane_model = fem::PlaneModel::kPlaneStrain;
  def.dirichlet.push_back({"top", {}, s.top_displacement});
  def.admissible.upper_bound = s.height / 2;
  def.admissible.height = s.height;
  def.initial_design = paraboloid_design(s);
  ContactDefinition contact;
  contact.law = s.law;
  contact.coulomb.method = s.method;
  contact.dense_delassus_max_unknowns = s.dense_max_unknowns;
  def.contact = contact;
  return def;
}

/// Distance of each contact node from the apex (centre of the base) in the x' plane.
inline Eigen::VectorXd apex_distances(const ElasticBody& body, double width) {
  const Eigen::MatrixXd& x = body.contact_boundary()->plane_coordinates();
  return (x.array() - width / 2).matrix().rowwise().norm();
}

/// Hertz theory for a rigid flat and an elastic parabolic body (Johnson, Contact Mechanics,
/// §4.2 and §5.1(a)), E* = E/(1 − ν²) (plane strain in 2D).
struct HertzPrediction {
  double radius = 0.0;    ///< a
  double pressure = 0.0;  ///< p0
};
inline HertzPrediction hertz(int dim, double load, double curvature_radius, double young, double poisson) {
  const double e_star = young / (1.0 - poisson * poisson);
  HertzPrediction h;
  if (dim == 3) {
    h.radius = std::cbrt(3.0 * load * curvature_radius / (4.0 * e_star));
    h.pressure = 3.0 * load / (2.0 * std::numbers::pi * h.radius * h.radius);
  } else {
    h.radius = std::sqrt(4.0 * load * curvature_radius / (std::numbers::pi * e_star));
    h.pressure = 2.0 * load / (std::numbers::pi * h.radius);
  }
  return h;
}

/// Radius of a semi-elliptic (Hertzian) distribution f(r) = f0·sqrt(1 − r²/a²) from nodal
/// forces F_i ≈ ∫ f N_i by its second moment about the apex: Σ F_i r_i² / Σ F_i equals
/// (2/5)a² in 3D (axisymmetric) and a²/4 in 2D. The nodal sums integrate f times the
/// interpolant of r², which differs from r² by O(h²), so the estimator is second-order
/// accurate and needs neither tributary areas nor a threshold for "in contact".
inline double moment_radius(int dim, const Eigen::VectorXd& forces, const Eigen::VectorXd& r) {
  const double m0 = forces.sum();
  const double m2 = forces.dot(r.cwiseAbs2());
  return std::sqrt((dim == 3 ? 2.5 : 4.0) * m2 / m0);
}

/// Least-squares fit of the Hertz profile to nodal pressures: p_i² = p0² − (p0²/a²) r_i² is
/// linear in r_i², fitted over the loaded nodes with r_i < `fraction`·a_guess (the nodes at
/// the rim carry a partly loaded tributary area, so their lumped pressure is biased).
struct ProfileFit {
  double radius = 0.0;
  double peak = 0.0;
  int points = 0;
};
inline ProfileFit fit_hertz_profile(const Eigen::VectorXd& pressure, const Eigen::VectorXd& r, double a_guess,
                                    double fraction) {
  double s0 = 0, s1 = 0, s2 = 0, t0 = 0, t1 = 0;
  int n = 0;
  for (Eigen::Index i = 0; i < pressure.size(); ++i) {
    if (pressure(i) <= 0 || r(i) >= fraction * a_guess) continue;
    const double x = r(i) * r(i), y = pressure(i) * pressure(i);
    s0 += 1; s1 += x; s2 += x * x; t0 += y; t1 += x * y;
    ++n;
  }
  const double det = s0 * s2 - s1 * s1;
  const double intercept = (s2 * t0 - s1 * t1) / det;
  const double slope = (s0 * t1 - s1 * t0) / det;
  ProfileFit fit;
  fit.points = n;
  fit.peak = std::sqrt(intercept);
  fit.radius = std::sqrt(-intercept / slope);
  return fit;
}

/// Wall-clock seconds since construction (printed in the tables, never asserted).
class Timer {
 public:
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

/// The linear term c = G A⁻¹ l + (0, g) of the dual QP at the body's last solved design, computed
/// from the factorization and the load (independently of the contact solver's output).
inline Eigen::VectorXd linear_term(const ElasticBody& body, const BodyState& state) {
  const Eigen::VectorXd u_free = body.elasticity().factorization().solve(body.elasticity().load());
  const contact::ContactBoundary& boundary = *body.contact_boundary();
  Eigen::VectorXd c = boundary.times(u_free);
  const int dim = boundary.dim();
  for (Eigen::Index i = 0; i < boundary.num_nodes(); ++i) c(dim * i + dim - 1) += state.contact->gaps(i);
  return c;
}

/// Frictionless oracle: projected Gauss–Seidel on the dense normal block of M = G A⁻¹ Gᵀ,
/// min ½λᵀM_νν λ + λᵀc_ν over λ >= 0, swept until the largest change is 1e-15 of max λ or
/// `max_sweeps` sweeps are spent. Callers must check `converged`: at the cap λ is not the oracle.
struct OracleResult {
  Eigen::VectorXd lambda;
  int sweeps = 0;          ///< sweeps done (the last one met the stopping test when converged)
  bool converged = false;  ///< the stopping test was met within max_sweeps
};
inline OracleResult frictionless_oracle(const ElasticBody& body, const BodyState& state, int max_sweeps = 1000000) {
  const contact::ContactBoundary& boundary = *body.contact_boundary();
  const Eigen::MatrixXd M = contact::dense_delassus(body.elasticity().factorization(), boundary);
  const Eigen::VectorXd c = linear_term(body, state);
  const int dim = boundary.dim();
  const Eigen::Index p = boundary.num_nodes();
  Eigen::MatrixXd Mn(p, p);
  Eigen::VectorXd cn(p);
  for (Eigen::Index i = 0; i < p; ++i) {
    cn(i) = c(dim * i + dim - 1);
    for (Eigen::Index j = 0; j < p; ++j) Mn(i, j) = M(dim * i + dim - 1, dim * j + dim - 1);
  }
  OracleResult out;
  out.lambda = Eigen::VectorXd::Zero(p);
  Eigen::VectorXd& lambda = out.lambda;
  while (out.sweeps < max_sweeps) {
    ++out.sweeps;
    double change = 0;
    for (Eigen::Index i = 0; i < p; ++i) {
      const double updated = std::max(0.0, lambda(i) - (Mn.row(i).dot(lambda) + cn(i)) / Mn(i, i));
      change = std::max(change, std::abs(updated - lambda(i)));
      lambda(i) = updated;
    }
    if (change <= 1e-15 * std::max(lambda.maxCoeff(), 1e-300)) {
      out.converged = true;
      break;
    }
  }
  return out;
}

/// The tangential parts q_i of z, stacked (p·(dim−1)).
inline Eigen::VectorXd tangential_forces(const contact::ContactState& st) {
  const int t = st.dim - 1;
  Eigen::VectorXd q(st.num_nodes() * t);
  for (Eigen::Index i = 0; i < st.num_nodes(); ++i)
    for (int c = 0; c < t; ++c) q(t * i + c) = st.z(st.dim * i + c);
  return q;
}

struct NodeCounts {
  int stick = 0, slip = 0, separated = 0;
};
inline NodeCounts count_nodes(const contact::ContactState& st) {
  NodeCounts n;
  for (Eigen::Index i = 0; i < st.num_nodes(); ++i) {
    if (st.is_stick(i)) ++n.stick;
    if (st.is_slip(i)) ++n.slip;
    if (st.is_separated(i)) ++n.separated;
  }
  return n;
}

/// Hertz quantities measured on a state, with the theory for the measured load.
struct HertzMeasurement {
  double load = 0.0;                ///< P = Σλ_i (2D: per metre)
  HertzPrediction theory;           ///< a, p0 from P
  double moment_radius = 0.0;       ///< a from the second moment of λ
  ProfileFit fit;                   ///< a, p0 from the least-squares profile fit
  double peak_pressure = 0.0;       ///< λ/area at the apex node
  double outermost_loaded = 0.0;    ///< largest r of a loaded (not separated) node
  double innermost_unloaded = 0.0;  ///< smallest r of a separated node
  double cell = 0.0;                ///< in-plane cell size h at the apex
};
inline HertzMeasurement measure_hertz(const ElasticBody& body, const BodyState& state, const BlockSpec& s) {
  const contact::ContactState& st = state.contact->state;
  const Eigen::VectorXd lambda = st.normal_forces();
  const Eigen::VectorXd pressure = lambda.cwiseQuotient(body.contact_boundary()->tributary_areas());
  const Eigen::VectorXd r = apex_distances(body, s.width);
  HertzMeasurement m;
  m.cell = apex_cell(s);
  m.load = lambda.sum();
  m.theory = hertz(s.dim, m.load, s.radius, s.young, s.poisson);
  m.moment_radius = moment_radius(s.dim, lambda, r);
  m.fit = fit_hertz_profile(pressure, r, m.moment_radius, 0.8);
  Eigen::Index apex = 0;
  r.minCoeff(&apex);
  m.peak_pressure = pressure(apex);
  m.innermost_unloaded = 1e300;
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    if (st.is_separated(i))
      m.innermost_unloaded = std::min(m.innermost_unloaded, r(i));
    else
      m.outermost_loaded = std::max(m.outermost_loaded, r(i));
  }
  return m;
}

/// One Markdown row of the Hertz tables.
inline void print_hertz_row(const HertzMeasurement& m, int cells, const BodyState& state, double seconds) {
  std::printf("| %d | %.1f | %.4e | %.5f | %.5f | %+.2f%% | %.5f | %+.2f%% | %.4e | %.4e | %+.2f%% | %.1e | %.1f |\n", cells,
              m.theory.radius / m.cell, m.load, m.theory.radius, m.moment_radius,
              100 * (m.moment_radius / m.theory.radius - 1), m.fit.radius, 100 * (m.fit.radius / m.theory.radius - 1),
              m.theory.pressure, m.peak_pressure, 100 * (m.peak_pressure / m.theory.pressure - 1),
              state.contact->summary.kkt_residual, seconds);
}

/// The stick zone of a 2D state (x = abscissa from the apex), see CattaneoMindlin2D.
struct StickZone {
  int stick = 0, slip = 0;
  double edges_half_width = 0.0;
  double moment_half_width = 0.0;
  double centre = 0.0;
  double normal_load = 0.0;      ///< P = Σλ
  double tangential_load = 0.0;  ///< Σq (the friction resistance, = −Σ τ)
};
inline StickZone measure_stick_zone(const contact::ContactState& st, const Eigen::VectorXd& x, double mu) {
  StickZone z;
  Eigen::VectorXd deficit(st.num_nodes());
  Eigen::Index first = -1, last = -1;
  for (Eigen::Index i = 0; i < st.num_nodes(); ++i) {
    const double lambda = st.lambda(i), q = st.z(2 * i);
    z.normal_load += lambda;
    z.tangential_load += q;
    deficit(i) = std::max(0.0, mu * lambda - std::abs(q));
    if (st.is_stick(i)) {
      ++z.stick;
      if (first < 0) first = i;
      last = i;
    }
    if (st.is_slip(i)) ++z.slip;
  }
  if (first < 0) return z;
  // Nodes are ordered by x; the edge lies midway between the last stick node and its neighbour.
  const double left = first > 0 ? 0.5 * (x(first) + x(first - 1)) : x(first);
  const double right = last + 1 < x.size() ? 0.5 * (x(last) + x(last + 1)) : x(last);
  z.edges_half_width = 0.5 * (right - left);
  z.centre = deficit.dot(x) / deficit.sum();
  z.moment_half_width = 2.0 * std::sqrt(deficit.dot((x.array() - z.centre).square().matrix()) / deficit.sum());
  return z;
}

/// Slope of the least-squares line through (x_k, y_k).
inline double least_squares_slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sx += x[k]; sy += y[k]; sxx += x[k] * x[k]; sxy += x[k] * y[k];
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

inline std::string fmt_rate(double rate) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", rate);
  return buf;
}

/// Relative error |a − b| / |b|.
inline double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

/// Tolerance of the KKT residual and complementarity gap on every case:
/// dimensionless, ~100× above the solvers' 1e-10 stopping tolerances.
inline constexpr double kResidualTolerance = 1e-8;

/// Asserts a converged state and checks the Coulomb residuals twice: as reported by the solver,
/// and recomputed from the FE displacement (∇ = (−u_t, u_ν + g) read off the body's nodes, so a
/// state whose displacement and forces disagree fails here).
inline void expect_valid_contact_state(const ElasticBody& body, const BodyState& state) {
  ASSERT_EQ(state.summary.status, Status::kConverged) << state.summary.brief_report();
  ASSERT_TRUE(state.contact.has_value());
  const ContactResult& c = *state.contact;
  EXPECT_LE(c.summary.kkt_residual, kResidualTolerance) << c.summary.brief_report();
  EXPECT_LE(c.summary.complementarity_gap, kResidualTolerance) << c.summary.brief_report();
  const contact::ContactBoundary& boundary = *body.contact_boundary();
  const int dim = boundary.dim();
  Eigen::VectorXd gradient = boundary.times_full(state.displacement);
  for (Eigen::Index i = 0; i < boundary.num_nodes(); ++i) gradient(dim * i + dim - 1) += c.gaps(i);
  const double scale = std::max(gradient.cwiseAbs().maxCoeff(), 1e-300);
  // The two routes to ∇ differ by the round-off of one more sparse solve: 1e-10 relative.
  EXPECT_LE((gradient - c.state.gradient).cwiseAbs().maxCoeff(), 1e-10 * scale);
  const std::vector<contact::FrictionLaw> laws = {body.definition().contact->law};
  const contact::ContactResiduals r =
      contact::contact_residuals(laws, c.state.normal_forces(), c.state.z, gradient, dim, scale);
  EXPECT_LE(r.kkt_residual, kResidualTolerance);
  EXPECT_LE(r.complementarity_gap, kResidualTolerance);
}

}  // namespace frictopt::study::validation
