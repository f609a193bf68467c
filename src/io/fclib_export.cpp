// SPDX-License-Identifier: MIT
// FCLIB local-problem export: our dual contact problem (docs/theory/state-problem.md §5) rewritten
// in FCLIB's variables, and the HDF5 file through fclib's C API (kept out of the public header).
#include "frictopt/io/fclib_export.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <limits>
#include <memory>
#include <system_error>
#include <vector>

extern "C" {
#include <fclib.h>
}

#include "atomic_file.hpp"
#include "child_process.hpp"
#include "frictopt/io/file_error.hpp"
#include "frictopt/contact/delassus.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/core/error.hpp"

#ifndef FRICTOPT_VERSION
#define FRICTOPT_VERSION "unknown"
#endif

namespace frictopt::io {
namespace {

constexpr double kTiny = std::numeric_limits<double>::min();

/// The isotropic coefficient of `law`, or InvalidInput naming the case spelling of the kind.
struct IsotropicReading {
  double mu = 0.0;
  bool exact = true;     // false: our law is the regular n-gon, the disc is exported instead
  std::string law_text;  // for the description
};

IsotropicReading isotropic_reading(const contact::FrictionLaw& law, std::string_view case_name) {
  using contact::FrictionLawKind;
  IsotropicReading out;
  out.law_text = law.describe();
  const auto reject = [&](const char* case_kind) {
    return InvalidInput(fmt::format(
        "{}{}contact.friction.kind = {} ({}) cannot be exported to FCLIB, which stores isotropic "
        "Coulomb cones only; use kind = disc_exact or isotropic{}",
        case_name, case_name.empty() ? "" : ": ", case_kind, law.describe(),
        law.dim() == 2 ? " (2D: mu_minus = mu_plus)" : ""));
  };
  switch (law.kind()) {
    case FrictionLawKind::kDisc:
      out.mu = law.max_coefficient();
      return out;
    case FrictionLawKind::kInterval: {
      // 2D: W = [−μ₋, μ₊] from the vertices (−μ₋, 0), (μ₊, 0); FCLIB's 2D cone is symmetric.
      const auto v = law.vertices();
      const double mu_minus = -v[0].x();
      const double mu_plus = v[1].x();
      if (mu_minus != mu_plus) throw reject("polygon");
      out.mu = mu_plus;
      return out;
    }
    case FrictionLawKind::kRegularPolygon:
      // The thesis' n-gon has its vertices on the circle of radius μ (docs/theory/state-problem.md
      // §3); their largest norm is μ to rounding (the law keeps no other copy of μ).
      out.mu = law.max_coefficient();
      out.exact = false;
      return out;
    case FrictionLawKind::kPolygon:
      throw reject("polygon");
    case FrictionLawKind::kEllipsePolygon:
      throw reject("ellipse");
    case FrictionLawKind::kEllipse:
      throw reject("ellipse_exact");
  }
  throw reject("unknown");
}

/// Projection onto the cone {‖t‖ <= μ n} of x = (n, t) (second-order cone, any tangent size).
Eigen::VectorXd project_on_cone(const Eigen::VectorXd& x, double mu) {
  const double n = x(0);
  const double t_norm = x.tail(x.size() - 1).norm();
  if (t_norm <= mu * n) return x;
  if (mu * t_norm <= -n) return Eigen::VectorXd::Zero(x.size());
  Eigen::VectorXd p(x.size());
  p(0) = (mu * t_norm + n) / (mu * mu + 1.0);
  p.tail(x.size() - 1) = (mu * p(0) / t_norm) * x.tail(x.size() - 1);
  return p;
}

// The dense Delassus matrix of the state: reused from the state solve when it kept one.
Eigen::MatrixXd state_delassus(const study::ContactResult& result, const linalg::SpdSolver& cholesky,
                               const contact::ContactBoundary& boundary) {
  if (result.delassus_matrix) return *result.delassus_matrix;
  if (const auto* schur = dynamic_cast<const contact::SchurDelassus*>(result.delassus.get())) return schur->dense();
  return contact::dense_delassus(cholesky, boundary);  // a state without its operator (released)
}

std::string case_label(const study::ElasticBody& body, const FclibExportOptions& options) {
  return options.case_name.empty() ? body.definition().name : options.case_name;
}

}  // namespace

void require_fclib_exportable(const contact::FrictionLaw& law, std::string_view case_name) {
  (void)isotropic_reading(law, case_name);
}

FclibLocalProblem make_fclib_local(const study::ElasticBody& body, const study::BodyState& state,
                                   const FclibExportOptions& options) {
  const std::string case_name = case_label(body, options);
  if (options.max_unknowns <= 0)
    throw InvalidInput(
        fmt::format("FclibExportOptions::max_unknowns = {}; expected > 0", options.max_unknowns));
  const contact::ContactBoundary* boundary = body.contact_boundary();
  if (boundary == nullptr || !body.definition().contact)
    throw InvalidInput(
        fmt::format("{}: the body has no foundation ([contact] is absent); there is no "
                    "frictional contact problem to export to FCLIB",
                    case_name));
  if (!state.contact)
    throw InvalidInput(
        fmt::format("{}: the state has no contact result (elasticity: {}); solve the "
                    "state before exporting it to FCLIB",
                    case_name, state.summary.message));
  const contact::FrictionLaw& law = body.definition().contact->law;
  const IsotropicReading reading = isotropic_reading(law, case_name);
  const study::ContactResult& result = *state.contact;
  const int d = boundary->dim();
  const Eigen::Index p = boundary->num_nodes();
  const Eigen::Index m = boundary->num_unknowns();
  if (m > options.max_unknowns)
    throw InvalidInput(fmt::format(
        "{}: {} contact unknowns ({} nodes × {}); the FCLIB export stores W densely and accepts at "
        "most FclibExportOptions::max_unknowns = {}",
        case_name, m, p, d, options.max_unknowns));
  if (result.state.z.size() != m || result.state.gradient.size() != m || result.gaps.size() != p)
    throw InvalidInput(fmt::format("{}: the contact state has {} unknowns; the body has {}",
                                   case_name, result.state.z.size(), m));

  // Our dual data (docs/theory/state-problem.md §5): M = G A⁻¹ Gᵀ as the state solve formed it (its
  // dense copy, or the dense M from its Schur factor: 2m³/3 flops, no second factorization of the
  // stiffness), c = G A⁻¹ l + (0, g) by one solve with the factorization of the last solve.
  const linalg::SpdSolver& cholesky = body.elasticity().factorization();
  const Eigen::MatrixXd M = state_delassus(result, cholesky, *boundary);
  Eigen::VectorXd c = boundary->times(cholesky.solve(body.elasticity().load()));
  for (Eigen::Index i = 0; i < p; ++i) c(d * i + d - 1) += result.gaps(i);

  // The state's operator must be this factorization's: M v against G A⁻¹ Gᵀ v for one v
  // (one solve), so a state of another design is refused even where its c happens to agree.
  {
    const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(m, 1.0, 2.0);
    Eigen::VectorXd w = Eigen::VectorXd::Zero(body.elasticity().dofs().num_free());
    boundary->add_transpose_times(v, w);
    const Eigen::VectorXd Mv = boundary->times(cholesky.solve(w));
    const double operator_mismatch = (M * v - Mv).norm() / std::max(Mv.norm(), kTiny);
    if (!(operator_mismatch <= 1e-8))
      throw InvalidInput(fmt::format("{}: the state is not the body's most recent solve (its Delassus operator "
                                     "differs from the body's factorization by {:.2e} relative); call "
                                     "body.solve(alpha) right before exporting",
                                     case_name, operator_mismatch));
  }
  // The state must come from this factorization: its gradient ∇ = Mz + c (a fresh apply in the
  // solver) must match ours to round-off. 1e-8 leaves room for the dense vs factorization-
  // applied Delassus (both backward stable, ~1e-14 relative) while any other design or load
  // changes ∇ at O(1).
  const Eigen::VectorXd& z = result.state.z;
  const Eigen::VectorXd gradient = M * z + c;
  const double scale =
      std::max({gradient.lpNorm<Eigen::Infinity>(), c.lpNorm<Eigen::Infinity>(), kTiny});
  const double mismatch = (gradient - result.state.gradient).lpNorm<Eigen::Infinity>() / scale;
  if (!(mismatch <= 1e-8))
    throw InvalidInput(
        fmt::format("{}: the state is not the body's most recent solve (its Mz + c differs "
                    "from the body's by {:.2e} relative); call body.solve(alpha) right "
                    "before exporting",
                    case_name, mismatch));

  // FCLIB ordering per contact: normal first, then tangential, r_T = τ = −q (the force on the
  // body) and u_T = u_t = −∇_q. With the signed permutation P (r = P z, u = P ∇):
  // W = P M Pᵀ, q = P c.
  std::vector<Eigen::Index> ours(static_cast<std::size_t>(m));
  Eigen::VectorXd sign(m);
  for (Eigen::Index i = 0; i < p; ++i) {
    ours[static_cast<std::size_t>(d * i)] = d * i + d - 1;
    sign(d * i) = 1.0;
    for (int k = 0; k < d - 1; ++k) {
      ours[static_cast<std::size_t>(d * i + 1 + k)] = d * i + k;
      sign(d * i + 1 + k) = -1.0;
    }
  }
  FclibLocalProblem out;
  out.spacedim = d;
  out.W = sign.asDiagonal() * M(ours, ours) * sign.asDiagonal();
  out.q = sign.asDiagonal() * c(ours);
  out.r = sign.asDiagonal() * z(ours);
  out.mu = Eigen::VectorXd::Constant(p, reading.mu);
  out.solution_is_exact = reading.exact && result.summary.converged();

  if (options.normalize_units) {
    const double r_scale = out.r.lpNorm<Eigen::Infinity>();
    const Eigen::VectorXd u_si = out.W * out.r + out.q;
    const double u_scale =
        std::max(u_si.lpNorm<Eigen::Infinity>(), out.q.lpNorm<Eigen::Infinity>());
    out.force_unit = r_scale > 0.0 ? r_scale : 1.0;
    out.length_unit = u_scale > 0.0 ? u_scale : 1.0;
    out.r /= out.force_unit;
    out.q /= out.length_unit;
    out.W *= out.force_unit / out.length_unit;
  }
  out.u = out.W * out.r + out.q;

  const char* what = d == 3 ? "3D" : "2D (plane, per metre of thickness)";
  out.title = fmt::format("frictopt {}: {}", FRICTOPT_VERSION, case_name);
  std::string law_note;
  if (!reading.exact)
    law_note = fmt::format(
        " The case uses kind = isotropic, i.e. the regular {}-gon inscribed in the disc of radius "
        "mu ({}); FCLIB stores isotropic cones only, so this file holds the disc (exact Coulomb "
        "cone) with the same mu, and the stored guess is frictopt's n-gon solution, not a solution "
        "of this problem.",
        law.vertices().size(), reading.law_text);
  else
    law_note = fmt::format(" Friction law: {}.", reading.law_text);
  out.description = fmt::format(
      "Static {} frictional contact problem of frictopt case '{}' (frictopt {}): an elastic body "
      "(linear elasticity, Q1 finite elements, {} free unknowns) on the rigid foundation "
      "x_{} <= 0, at design alpha = [{}], {} potential contact nodes (the bottom nodes, frame = "
      "global axes, normal e_{} upward). Isotropic Coulomb friction, mu = {}.{} Static reading "
      "of FCLIB's velocities: u_N = u_nu + g is the gap after deformation and u_T the tangential "
      "displacement at the node; r = (lambda, tau) are the nodal contact forces on the body "
      "(normal first). Units: {} forces in {:.17g} N{}, displacements in {:.17g} m. Our solution "
      "(Coulomb fixed point over Tresca dual QPs): {}.",
      what, case_name, FRICTOPT_VERSION, body.elasticity().dofs().num_free(), d,
      fmt::join(state.alpha.data(), state.alpha.data() + state.alpha.size(), ", "), p, d,
      reading.mu, law_note,
      options.normalize_units ? "normalized (frictopt's default: W, q, r and u are O(1) so that other solvers' "
                                "absolute tolerances read as relative ones; multiply back by these units for SI):"
                              : "SI:",
      out.force_unit, d == 2 ? " per metre" : "", out.length_unit,
      result.summary.brief_report());
  out.math_info = fmt::format(
      "W = H A^-1 H^T with A the stiffness matrix on the free degrees of freedom (symmetric "
      "positive definite: Dirichlet conditions remove rigid motions) and H selecting the "
      "(normal, tangential) displacements of distinct contact nodes (full rank), so W is "
      "symmetric positive definite and dense. A solution exists for every mu >= 0; uniqueness is "
      "only known for small mu. q = H A^-1 l + (g, 0{}) per contact, g >= 0 the initial gaps.",
      d == 3 ? ", 0" : "");
  return out;
}

void write_fclib_local(const std::filesystem::path& path, const FclibLocalProblem& problem,
                       bool include_solution) {
  const Eigen::Index m = problem.W.rows();
  if (problem.spacedim != 2 && problem.spacedim != 3)
    throw InvalidInput(fmt::format("{}: FclibLocalProblem::spacedim = {}; expected 2 or 3",
                                   path.string(), problem.spacedim));
  if (m == 0 || problem.W.cols() != m || problem.q.size() != m || m % problem.spacedim != 0 ||
      problem.mu.size() != m / problem.spacedim || problem.r.size() != m || problem.u.size() != m)
    throw InvalidInput(
        fmt::format("{}: inconsistent FCLIB problem sizes (W {}×{}, q {}, mu {}, r {}, u {}, "
                    "spacedim {}); expected W m×m with m > 0 a multiple of spacedim",
                    path.string(), problem.W.rows(), problem.W.cols(), problem.q.size(),
                    problem.mu.size(), problem.r.size(), problem.u.size(), problem.spacedim));
  if (m > 46340)  // m² must fit FCLIB's int nzmax
    throw InvalidInput(fmt::format("{}: W has {} rows; a dense FCLIB matrix holds at most 46340",
                                   path.string(), m));
  const std::filesystem::path parent =
      path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  if (!std::filesystem::is_directory(parent))
    throw InvalidInput(fmt::format("{}: cannot write the FCLIB file: directory {} does not exist",
                                   path.string(), parent.string()));

  // fclib's writers append to an existing HDF5 file (and refuse to overwrite a problem), so
  // write a fresh, uniquely named sibling and rename it over the target if that is a regular
  // file (atomic_file.hpp). fclib creates the file itself: the reserved empty name is freed.
  const std::filesystem::path partial = detail::make_sibling_temporary(path);
  std::error_code ignored;
  std::filesystem::remove(partial, ignored);

  // Dense W as compressed columns (nz = −1): Eigen stores column-major, so x is W.data().
  const int n = static_cast<int>(m);
  std::vector<int> column_start(static_cast<std::size_t>(n) + 1);
  std::vector<int> row(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
  for (int j = 0; j <= n; ++j) column_start[static_cast<std::size_t>(j)] = j * n;
  for (std::size_t k = 0; k < row.size(); ++k)
    row[k] = static_cast<int>(k % static_cast<std::size_t>(n));
  Eigen::MatrixXd W = problem.W;  // fclib takes non-const pointers
  Eigen::VectorXd q = problem.q, mu = problem.mu, r = problem.r, u = problem.u;
  std::string title = problem.title, description = problem.description,
              math_info = problem.math_info;

  fclib_matrix w_matrix{};
  w_matrix.nzmax = n * n;
  w_matrix.m = n;
  w_matrix.n = n;
  w_matrix.p = column_start.data();
  w_matrix.i = row.data();
  w_matrix.x = W.data();
  w_matrix.nz = -1;
  w_matrix.info = nullptr;
  fclib_info info{title.data(), description.data(), math_info.data()};
  fclib_local local{};
  local.W = &w_matrix;
  local.V = nullptr;
  local.R = nullptr;
  local.mu = mu.data();
  local.q = q.data();
  local.s = nullptr;
  local.spacedim = problem.spacedim;
  local.info = &info;

  // fclib ends the process (exit(1), after HDF5's error stack) when an HDF5 call fails — on a
  // full disk or a read-only file system — so the file is written by a child process: its
  // failure is then an answer (FileSystemError, the previous file kept), not the end of the
  // caller (the command line, or the Python interpreter).
  fclib_solution solution{nullptr, u.data(), r.data(), nullptr};
  const auto write_all_parts = [&]() -> int {
    if (fclib_write_local(&local, partial.c_str()) != 1) return 2;
    if (include_solution) {
      if (problem.solution_is_exact) {
        if (fclib_write_solution(&solution, partial.c_str()) != 1) return 3;
      } else if (fclib_write_guesses(1, &solution, partial.c_str()) != 1) {
        return 4;
      }
    }
    return 0;
  };
  const detail::ChildResult child = detail::run_in_child(write_all_parts);
  if (child.exit_code != 0) {
    std::filesystem::remove(partial, ignored);
    const char* part = child.exit_code == 3 ? "solution" : child.exit_code == 4 ? "initial guess" : "local problem";
    throw FileSystemError(fmt::format("{}: fclib/HDF5 could not write the {} (a full disk or a read-only file "
                                      "system?); the previous file is kept{}{}",
                                      path.string(), part, child.diagnostics.empty() ? "" : ". HDF5 said: ",
                                      child.diagnostics),
                          path, child.exit_code == 0 ? 0 : EIO);
  }
  detail::publish_file(partial, path);
}

FclibLocalProblem export_fclib_local(const std::filesystem::path& path,
                                     const study::ElasticBody& body, const study::BodyState& state,
                                     const FclibExportOptions& options) {
  FclibLocalProblem problem = make_fclib_local(body, state, options);
  write_fclib_local(path, problem, options.include_solution);
  return problem;
}

double fclib_natural_map_residual(const FclibLocalProblem& problem,
                                  const Eigen::Ref<const Eigen::VectorXd>& r) {
  const int d = problem.spacedim;
  const Eigen::VectorXd u = problem.W * r + problem.q;
  const double R = std::max(r.lpNorm<Eigen::Infinity>(), kTiny);
  const double U =
      std::max({u.lpNorm<Eigen::Infinity>(), problem.q.lpNorm<Eigen::Infinity>(), kTiny});
  const double rho = R / U;
  double worst = 0.0;
  for (Eigen::Index i = 0; i < problem.num_contacts(); ++i) {
    const Eigen::VectorXd ri = r.segment(d * i, d);
    Eigen::VectorXd u_hat = u.segment(d * i, d);
    u_hat(0) += problem.mu(i) * u_hat.tail(d - 1).norm();  // De Saxcé's modified velocity
    const Eigen::VectorXd e = ri - project_on_cone(ri - rho * u_hat, problem.mu(i));
    worst = std::max(worst, e.norm());
  }
  return worst / R;
}

}  // namespace frictopt::io
