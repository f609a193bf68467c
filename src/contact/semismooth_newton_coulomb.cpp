// SPDX-License-Identifier: MIT
#include "frictopt/contact/semismooth_newton_coulomb.hpp"

#include <Eigen/LU>
#include <Eigen/QR>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "frictopt/contact/delassus.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/core/validation.hpp"
#include "frictopt/linalg/dense_blas.hpp"

namespace frictopt::contact {
namespace {

// Armijo constant and step floor of the line search on θ = ½‖Φ‖² (Hintermüller, Ito & Kunisch
// 2002 use the same sufficient decrease θ(z + t d) <= (1 − 2σt) θ(z)).
constexpr double kArmijo = 1e-4;
constexpr double kMinStep = 1.0 / 1024.0 / 1024.0;
// Tolerance of the frictionless start's Tresca QP: only a starting point.
constexpr double kStartTolerance = 1e-6;
// Inexact Newton forcing term (Eisenstat & Walker 1996): the linear residual relative to ‖Φ‖ is
// at most min(kMaxForcing, ‖Φ_k‖/‖Φ_0‖), so the steps are Newton's near the solution.
constexpr double kMaxForcing = 1e-3;
constexpr double kMinForcing = 1e-13;

const FrictionLaw& law_of(const std::vector<FrictionLaw>& laws, Eigen::Index i) {
  return laws.size() == 1 ? laws[0] : laws[static_cast<std::size_t>(i)];
}

Eigen::Vector2d tangential_of(const Eigen::Ref<const Eigen::VectorXd>& v, int dim, Eigen::Index i) {
  return dim == 3 ? Eigen::Vector2d(v(3 * i), v(3 * i + 1)) : Eigen::Vector2d(v(2 * i), 0.0);
}

/// P = proj_{sW}(x) and its derivatives: P(x, s) = s·P_W(x/s) is positively homogeneous, so with
/// y = x/s, ∂P/∂x = J_W(y) and ∂P/∂s = P_W(y) − J_W(y)·y (J_W the law's
/// projection_jacobian); s = 0 or W = {0}: P = 0 with zero derivatives (as the PETSc engine's
/// linearize_projection, docs/petsc-engine.md).
struct ScaledProjection {
  Eigen::Vector2d value = Eigen::Vector2d::Zero();
  Eigen::Matrix2d d_x = Eigen::Matrix2d::Zero();
  Eigen::Vector2d d_s = Eigen::Vector2d::Zero();
};
ScaledProjection scaled_projection(const FrictionLaw& law, const Eigen::Vector2d& x, double s) {
  ScaledProjection out;
  if (!(s > 0.0) || law.is_zero()) return out;
  Eigen::Vector2d y = x / s;
  if (law.dim() == 2) y.y() = 0.0;
  const FrictionLaw::ProjectionJacobian p = law.projection_jacobian(y);
  out.value = s * p.point;
  out.d_x = p.jacobian;
  out.d_s = p.point - p.jacobian * y;
  return out;
}

using Block = Eigen::Matrix3d;

/// Φ at z (with ∇ = Mz + c) and, optionally, the blocks of J = A + (R D) M: per node the
/// dim × dim blocks A_i = I − D_i − E_i and RD_i = r_i D_i.
struct Linearization {
  std::vector<Block> a, rd;
};

Eigen::VectorXd alart_curnier(const std::vector<FrictionLaw>& laws, const Eigen::VectorXd& r, const Eigen::VectorXd& z,
                              const Eigen::VectorXd& g, int dim, Linearization* lin) {
  const Eigen::Index p = r.size();
  const int nt = dim - 1;
  Eigen::VectorXd phi(z.size());
  if (lin) {
    lin->a.assign(static_cast<std::size_t>(p), Block::Zero());
    lin->rd.assign(static_cast<std::size_t>(p), Block::Zero());
  }
  for (Eigen::Index i = 0; i < p; ++i) {
    const Eigen::Index b = dim * i;
    const double lambda = z(b + nt), w = g(b + nt), ri = r(i);
    const double y_n = lambda - ri * w;
    phi(b + nt) = lambda - std::max(0.0, y_n);
    const Eigen::Vector2d q = tangential_of(z, dim, i);
    const Eigen::Vector2d x = q - ri * tangential_of(g, dim, i);
    const ScaledProjection pr = scaled_projection(law_of(laws, i), x, std::max(lambda, 0.0));
    for (int k = 0; k < nt; ++k) phi(b + k) = q(k) - pr.value(k);
    if (!lin) continue;
    Block d = Block::Zero();
    d.topLeftCorner(nt, nt) = pr.d_x.topLeftCorner(nt, nt);
    d(nt, nt) = y_n > 0.0 ? 1.0 : 0.0;
    Block& a = lin->a[static_cast<std::size_t>(i)];
    a.topLeftCorner(dim, dim).setIdentity();
    a.topLeftCorner(dim, dim) -= d.topLeftCorner(dim, dim);
    // E: ∂P_t/∂λ through the slip bound [λ]₊ (zero where λ <= 0).
    if (lambda > 0.0)
      for (int k = 0; k < nt; ++k) a(k, nt) -= pr.d_s(k);
    lin->rd[static_cast<std::size_t>(i)] = ri * d;
  }
  return phi;
}

/// y = A v + RD (M v) over the contact rows, with `mv` = M v given (M v + Eᵀ v_β for a
/// floating body, whose balance rows the caller appends).
void jacobian_times(const Linearization& lin, int dim, const Eigen::Ref<const Eigen::VectorXd>& v,
                    const Eigen::VectorXd& mv, Eigen::Ref<Eigen::VectorXd> y) {
  const Eigen::Index p = static_cast<Eigen::Index>(lin.a.size());
  for (Eigen::Index i = 0; i < p; ++i) {
    const Eigen::Index b = dim * i;
    const Block& a = lin.a[static_cast<std::size_t>(i)];
    const Block& rd = lin.rd[static_cast<std::size_t>(i)];
    y.segment(b, dim) = a.topLeftCorner(dim, dim) * v.segment(b, dim) + rd.topLeftCorner(dim, dim) * mv.segment(b, dim);
  }
}

/// The dense J = A + RD·M (row blocks), in the scalar type T; with balance rows E (r > 0) the
/// bordered [A + RD·M, RD·Eᵀ; E, 0] of a floating body.
template <class T>
Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic> dense_jacobian(const Linearization& lin, const Eigen::MatrixXd& m,
                                                                const Eigen::MatrixXd& e, int dim) {
  const Eigen::Index n = m.rows(), p = static_cast<Eigen::Index>(lin.a.size()), r = e.rows();
  Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic> j(n + r, n + r);
  for (Eigen::Index i = 0; i < p; ++i) {
    const Eigen::Index b = dim * i;
    const Eigen::MatrixXd rd = lin.rd[static_cast<std::size_t>(i)].topLeftCorner(dim, dim);
    // M is symmetric: its rows are its columns, read contiguously.
    j.block(b, 0, dim, n) = (rd * m.middleCols(b, dim).transpose()).template cast<T>();
    j.block(b, b, dim, dim) += lin.a[static_cast<std::size_t>(i)].topLeftCorner(dim, dim).template cast<T>();
    if (r > 0) j.block(b, n, dim, r) = (rd * e.middleCols(b, dim).transpose()).template cast<T>();
  }
  if (r > 0) {
    j.bottomLeftCorner(r, n) = e.template cast<T>();
    j.bottomRightCorner(r, r).setZero();
  }
  return j;
}

/// Right-preconditioned GMRES without restart (Saad & Schultz 1986) for J x = b from the given
/// x: written here rather than taken from Eigen's unsupported module because the forcing term
/// of the inexact Newton step bounds the true residual ‖b − J x‖, which right preconditioning
/// keeps and Eigen's left-preconditioned GMRES does not. Returns the iterations; `converged`
/// tells whether ‖b − J x‖ <= tol·‖b‖ (the recurrence's estimate).
template <class ApplyJ, class ApplyP>
int gmres(const ApplyJ& apply_j, const ApplyP& apply_p, const Eigen::VectorXd& b, Eigen::VectorXd& x, double tol,
          int max_iterations, bool& converged) {
  const Eigen::Index n = b.size();
  Eigen::VectorXd r(n), w(n);
  apply_j(x, w);
  r = b - w;
  const double b_norm = b.norm();
  double beta = r.norm();
  converged = beta <= tol * b_norm;
  if (converged || max_iterations == 0) return 0;
  const int k_max = max_iterations;
  Eigen::MatrixXd v(n, k_max + 1), h = Eigen::MatrixXd::Zero(k_max + 1, k_max);
  Eigen::VectorXd cs = Eigen::VectorXd::Zero(k_max), sn = Eigen::VectorXd::Zero(k_max);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(k_max + 1);
  e(0) = beta;
  v.col(0) = r / beta;
  int k = 0;
  Eigen::VectorXd pv(n);
  while (k < k_max) {
    pv = v.col(k);
    apply_p(pv);
    apply_j(pv, w);
    for (int i = 0; i <= k; ++i) {  // modified Gram–Schmidt
      h(i, k) = v.col(i).dot(w);
      w -= h(i, k) * v.col(i);
    }
    h(k + 1, k) = w.norm();
    if (h(k + 1, k) > 0.0) v.col(k + 1) = w / h(k + 1, k);
    for (int i = 0; i < k; ++i) {  // the previous rotations
      const double t = cs(i) * h(i, k) + sn(i) * h(i + 1, k);
      h(i + 1, k) = -sn(i) * h(i, k) + cs(i) * h(i + 1, k);
      h(i, k) = t;
    }
    const double denom = std::hypot(h(k, k), h(k + 1, k));
    cs(k) = denom > 0.0 ? h(k, k) / denom : 1.0;
    sn(k) = denom > 0.0 ? h(k + 1, k) / denom : 0.0;
    h(k, k) = denom;
    h(k + 1, k) = 0.0;
    e(k + 1) = -sn(k) * e(k);
    e(k) = cs(k) * e(k);
    ++k;
    if (std::abs(e(k)) <= tol * b_norm || denom == 0.0) break;
  }
  const Eigen::VectorXd y = h.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(e.head(k));
  Eigen::VectorXd dx = v.leftCols(k) * y;
  apply_p(dx);
  x += dx;
  apply_j(x, w);
  converged = (b - w).norm() <= tol * b_norm * 1.01;
  return k;
}

/// z projected onto its own feasible set: λ ← max(λ, 0), q ← P_{λW}(q).
void project_feasible(const std::vector<FrictionLaw>& laws, int dim, Eigen::VectorXd& z) {
  const Eigen::Index p = z.size() / dim;
  for (Eigen::Index i = 0; i < p; ++i) {
    const Eigen::Index b = dim * i;
    const double lambda = std::max(z(b + dim - 1), 0.0);
    z(b + dim - 1) = lambda;
    const Eigen::Vector2d q = law_of(laws, i).project(tangential_of(z, dim, i), lambda);
    z(b) = q.x();
    if (dim == 3) z(b + 1) = q.y();
  }
}

}  // namespace

double coulomb_projected_gradient_norm(std::span<const FrictionLaw> laws, const Eigen::Ref<const Eigen::VectorXd>& z,
                                       const Eigen::Ref<const Eigen::VectorXd>& gradient, int dim, double alpha) {
  const Eigen::Index p = z.size() / dim;
  FRICTOPT_ASSERT(gradient.size() == z.size() && (laws.size() == 1 || static_cast<Eigen::Index>(laws.size()) == p),
                  "coulomb_projected_gradient_norm: size mismatch");
  double sum = 0.0;
  for (Eigen::Index i = 0; i < p; ++i) {
    const FrictionLaw& law = laws.size() == 1 ? laws[0] : laws[static_cast<std::size_t>(i)];
    const double lambda = z(dim * i + dim - 1), gn = gradient(dim * i + dim - 1);
    const double t_n = (lambda - std::max(0.0, lambda - alpha * gn)) / alpha;
    const Eigen::Vector2d q = tangential_of(z, dim, i);
    const Eigen::Vector2d t_q = (q - law.project(q - alpha * tangential_of(gradient, dim, i), std::max(lambda, 0.0))) / alpha;
    sum += t_n * t_n + t_q.squaredNorm();
  }
  return std::sqrt(sum);
}

SemismoothNewtonCoulombSolver::SemismoothNewtonCoulombSolver(const linalg::LinearOperator& delassus,
                                                             const FrictionLaw& law, CoulombSolver::Options options)
    : SemismoothNewtonCoulombSolver(delassus, std::vector<FrictionLaw>{law}, std::move(options)) {}

namespace {
CoulombSolver::Options fixed_point_options(CoulombSolver::Options options) {
  options.validate();
  options.method = CoulombMethod::kFixedPoint;
  return options;
}
}  // namespace

SemismoothNewtonCoulombSolver::SemismoothNewtonCoulombSolver(const linalg::LinearOperator& delassus,
                                                             std::vector<FrictionLaw> laws,
                                                             CoulombSolver::Options options)
    : delassus_(delassus),
      laws_(laws),
      options_(std::move(options)),
      fixed_point_(delassus, std::move(laws), fixed_point_options(options_)) {
  dim_ = fixed_point_.tresca().dim();
  num_nodes_ = fixed_point_.tresca().num_nodes();
  if (const auto* dense = dynamic_cast<const DenseDelassus*>(&delassus_)) {
    matrix_ = &dense->matrix();
  } else if (const auto* op = dynamic_cast<const linalg::DenseOperator*>(&delassus_)) {
    matrix_ = &op->matrix();
  } else {
    // M formed by m products (the Newton Jacobian and its LU need the entries).
    const Eigen::Index m = delassus_.size();
    formed_.emplace(m, m);
    Eigen::VectorXd e = Eigen::VectorXd::Zero(m), col(m);
    for (Eigen::Index j = 0; j < m; ++j) {
      e(j) = 1.0;
      delassus_.apply(e, col);
      formed_->col(j) = col;
      e(j) = 0.0;
    }
    matrix_ = &*formed_;
  }
}

CoulombSolver::Summary SemismoothNewtonCoulombSolver::solve(const Eigen::Ref<const Eigen::VectorXd>& c,
                                                            ContactState& state) const {
  const auto start = std::chrono::steady_clock::now();
  const Eigen::Index m = delassus_.size();
  if (c.size() != m)
    throw InvalidInput("SemismoothNewtonCoulombSolver::solve: c has size " + std::to_string(c.size()) +
                       "; expected " + std::to_string(m));
  if (!c.allFinite()) throw InvalidInput("SemismoothNewtonCoulombSolver::solve: c has non-finite entries");
  const Eigen::VectorXd cc = c;
  const ContactState initial = state;
  Eigen::VectorXd no_beta;
  CoulombSolver::Summary summary = iterate(cc, nullptr, state, no_beta);
  if (summary.converged() || !options_.newton.fallback_to_fixed_point) {
    fixed_point_.finish(cc, state, summary);
  } else {
    // The fixed point from the same start (docs/contact.md, "Semismooth Newton": the fallback).
    const std::string why = summary.message;
    state = initial;
    CoulombSolver::Summary fp = fixed_point_.solve(cc, state);
    fp.method_given = CoulombMethod::kSemismoothNewton;
    fp.fallback = true;
    fp.newton_iterations = summary.newton_iterations;
    fp.linear_iterations = summary.linear_iterations;
    fp.factorizations = summary.factorizations;
    fp.operator_applications += summary.operator_applications;
    fp.message = "semismooth Newton failed (" + why + "); fixed point: " + fp.message;
    summary = std::move(fp);
  }
  summary.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

double SemismoothNewtonCoulombSolver::Balance::residual(const Eigen::Ref<const Eigen::VectorXd>& z) const {
  return (equality * z - rhs).norm() /
         std::max({rhs.norm(), equality.norm() * z.norm(), std::numeric_limits<double>::min()});
}

CoulombSolver::Summary SemismoothNewtonCoulombSolver::solve_balanced(const Eigen::Ref<const Eigen::VectorXd>& c,
                                                                     const Balance& balance, ContactState& state,
                                                                     Eigen::VectorXd& beta) const {
  const auto start = std::chrono::steady_clock::now();
  const Eigen::Index m = delassus_.size();
  if (c.size() != m || balance.equality.cols() != m || balance.rhs.size() != balance.equality.rows())
    throw InvalidInput("SemismoothNewtonCoulombSolver::solve_balanced: c has size " + std::to_string(c.size()) +
                       ", E is " + std::to_string(balance.equality.rows()) + " × " +
                       std::to_string(balance.equality.cols()) + " and e has size " +
                       std::to_string(balance.rhs.size()) + "; expected c and E's rows of size " +
                       std::to_string(m) + ", e of E's row count");
  if (!c.allFinite() || !balance.rhs.allFinite())
    throw InvalidInput("SemismoothNewtonCoulombSolver::solve_balanced: non-finite c or e");
  const Eigen::VectorXd cc = c;
  CoulombSolver::Summary summary = iterate(cc, &balance, state, beta);
  // The classification's scales from the effective linear term c + Eᵀβ.
  fixed_point_.finish(cc + balance.equality.transpose() * beta, state, summary);
  summary.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

CoulombSolver::Summary SemismoothNewtonCoulombSolver::iterate(const Eigen::VectorXd& c, const Balance* balance,
                                                              ContactState& state, Eigen::VectorXd& beta) const {
  CoulombSolver::Summary summary;
  summary.method_given = summary.method_used = CoulombMethod::kSemismoothNewton;
  const int dim = dim_;
  const Eigen::Index m = c.size(), p = num_nodes_;
  const Eigen::MatrixXd& mat = *matrix_;
  // The balance rows (none for a body held by its Dirichlet conditions: r = 0).
  const Eigen::MatrixXd no_rows(0, m);
  const Eigen::VectorXd no_rhs(0);
  const Eigen::MatrixXd& E = balance ? balance->equality : no_rows;
  const Eigen::VectorXd& e = balance ? balance->rhs : no_rhs;
  const Eigen::Index nb = E.rows();
  if (beta.size() != nb) beta = Eigen::VectorXd::Zero(nb);
  const auto apply_m = [&](const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd& y) {
    y.resize(m);
    delassus_.apply(x, y);
    ++summary.operator_applications;
  };
  // ∇ = Mz + c + Eᵀβ.
  const auto gradient_at = [&](const Eigen::VectorXd& zz, const Eigen::VectorXd& bb, Eigen::VectorXd& gg) {
    apply_m(zz, gg);
    gg += c;
    if (nb > 0) gg.noalias() += E.transpose() * bb;
  };
  // The balance residual relative to the loads; 0 without rows.
  const auto balance_error = [&](const Eigen::VectorXd& zz) { return balance ? balance->residual(zz) : 0.0; };
  const double balance_target = balance ? balance->tolerance : 0.0;
  // Start: the warm start, or the frictionless problem.
  Eigen::VectorXd z;
  if (state.z.size() == m && state.dim == dim) {
    z = state.z;
  } else {
    ContactState frictionless(dim, p);
    const TrescaSolver::Summary qp =
        fixed_point_.tresca().solve_to(c, Eigen::VectorXd::Zero(p), frictionless, kStartTolerance);
    summary.qp_iterations += qp.iterations;
    summary.operator_applications += qp.operator_applications;
    z = frictionless.z;
  }
  project_feasible(laws_, dim, z);
  // r_i = dim / trace(M_ii): Φ's two terms in the same units, J's diagonal near 1 where active.
  Eigen::VectorXd r(p);
  for (Eigen::Index i = 0; i < p; ++i) {
    const double trace = mat.block(dim * i, dim * i, dim, dim).trace();
    r(i) = trace > 0.0 ? dim / trace : 1.0;
  }
  // The projected gradient relative to the linear term: c, or c + Eᵀβ for a floating body (the
  // loads the contact balances).
  const auto linear_norm = [&](const Eigen::VectorXd& bb) {
    const double n = nb > 0 ? (c + E.transpose() * bb).norm() : c.norm();
    return n > 0.0 ? n : 1.0;
  };
  const double alpha = fixed_point_.tresca().step_length();
  const double target = options_.tresca.relative_tolerance;
  const auto finish_state = [&](const Eigen::VectorXd& zz, const Eigen::VectorXd& gg) {
    state = ContactState(dim, p);
    state.z = zz;
    state.gradient = gg;
  };

  Eigen::VectorXd g(m), md(m), phi_t, psi_t, g_t(m), z_t(m), zc(m), gc(m), mv(m), ed(nb);
  Eigen::VectorXd d(m + nb), f(m + nb);
  gradient_at(z, beta, g);
  Linearization lin;
  Eigen::VectorXd phi = alart_curnier(laws_, r, z, g, dim, &lin);
  Eigen::VectorXd psi = E * z - e;
  const auto residual_norm = [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    return std::sqrt(a.squaredNorm() + b.squaredNorm());
  };
  const double phi0 = std::max(residual_norm(phi, psi), std::numeric_limits<double>::min());
  linalg::blas::SinglePrecisionLu preconditioner;
  bool have_preconditioner = false;
  const bool direct = m <= options_.newton.direct_max_unknowns;
  for (int k = 0;; ++k) {
    if (!phi.allFinite() || !psi.allFinite()) {
      summary.status = Status::kNumericalFailure;
      summary.message = "non-finite Alart–Curnier residual";
      break;
    }
    // The fixed point's inner stopping quantity at s = λ, on the feasible projection of z.
    const double rpg = coulomb_projected_gradient_norm(laws_, z, g, dim, alpha) / linear_norm(beta);
    summary.relative_projected_gradient = rpg;
    if ((rpg <= target && balance_error(z) <= balance_target) || residual_norm(phi, psi) == 0.0) {
      zc = z;
      project_feasible(laws_, dim, zc);
      gradient_at(zc, beta, gc);
      const double rpg_c = coulomb_projected_gradient_norm(laws_, zc, gc, dim, alpha) / linear_norm(beta);
      if (rpg_c <= target && balance_error(zc) <= balance_target) {
        summary.status = Status::kConverged;
        summary.relative_projected_gradient = rpg_c;
        finish_state(zc, gc);
        return summary;
      }
    }
    if (k >= options_.newton.max_iterations) {
      summary.status = Status::kMaxIterations;
      summary.message = "newton.max_iterations = " + std::to_string(options_.newton.max_iterations) +
                        " reached; projected gradient " + format_number(rpg) +
                        (nb > 0 ? ", balance residual " + format_number(balance_error(z)) : std::string());
      break;
    }
    // The Newton step J d = −(Φ, Ez − e).
    f.head(m) = -phi;
    f.tail(nb) = -psi;
    d.setZero();
    if (direct) {
      const Eigen::MatrixXd jacobian = dense_jacobian<double>(lin, mat, E, dim);
      const Eigen::PartialPivLU<Eigen::MatrixXd> lu(jacobian);
      ++summary.factorizations;
      ++summary.linear_iterations;
      d = lu.solve(f);
      // A singular Jacobian (a degenerate active set, e.g. every node of a floating body slipping
      // at a polygon's vertex, where β moves no row): the least-squares step of least norm, which
      // the line search then judges like any other.
      if (!d.allFinite()) {
        d = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(jacobian).solve(f);
        ++summary.factorizations;
      }
    } else {
      const double eta = std::clamp(residual_norm(phi, psi) / phi0, kMinForcing, kMaxForcing);
      const auto apply_j = [&](const Eigen::VectorXd& v, Eigen::VectorXd& y) {
        y.resize(m + nb);
        apply_m(v.head(m), mv);
        if (nb > 0) mv.noalias() += E.transpose() * v.tail(nb);
        jacobian_times(lin, dim, v.head(m), mv, y.head(m));
        if (nb > 0) y.tail(nb).noalias() = E * v.head(m);
      };
      const auto apply_p = [&](Eigen::VectorXd& v) { preconditioner.solve_in_place(v); };
      bool ok = false;
      if (have_preconditioner)
        summary.linear_iterations += gmres(apply_j, apply_p, f, d, eta, options_.newton.gmres_max_iterations, ok);
      if (!ok) {
        // The last factorization's Jacobian is too far from this one: factorize this one.
        if (!preconditioner.factorize(dense_jacobian<float>(lin, mat, E, dim))) {
          summary.status = Status::kNumericalFailure;
          summary.message = "singular Newton Jacobian";
          break;
        }
        have_preconditioner = true;
        ++summary.factorizations;
        summary.linear_iterations += gmres(apply_j, apply_p, f, d, eta, 2 * options_.newton.gmres_max_iterations, ok);
      }
    }
    if (!d.allFinite()) {
      summary.status = Status::kNumericalFailure;
      summary.message = "non-finite Newton step (singular Jacobian)";
      break;
    }
    // Line search (Armijo on θ = ½‖Φ‖² + ½‖Ez − e‖²); ∇ along the step is g + t·(M d_z + Eᵀd_β).
    apply_m(d.head(m), md);
    if (nb > 0) {
      md.noalias() += E.transpose() * d.tail(nb);
      ed.noalias() = E * d.head(m);
    }
    const double theta = 0.5 * (phi.squaredNorm() + psi.squaredNorm());
    double t = 1.0;
    bool accepted = false;
    for (; t >= kMinStep; t *= 0.5) {
      z_t = z + t * d.head(m);
      g_t = g + t * md;
      phi_t = alart_curnier(laws_, r, z_t, g_t, dim, nullptr);
      psi_t = psi + t * ed;
      if (0.5 * (phi_t.squaredNorm() + psi_t.squaredNorm()) <= (1.0 - 2.0 * kArmijo * t) * theta) {
        accepted = true;
        break;
      }
    }
    ++summary.newton_iterations;
    summary.iterations = 0;
    if (!accepted) {
      summary.status = Status::kDiverged;
      summary.message = "no sufficient decrease of ½‖Φ‖² along the Newton step (step " + format_number(t) +
                        ") at Newton step " + std::to_string(k + 1) + ", projected gradient " + format_number(rpg);
      break;
    }
    z = z_t;
    if (nb > 0) beta += t * d.tail(nb);
    // A fresh ∇ every few steps keeps the updated one from drifting by rounding.
    if ((k + 1) % 8 == 0) {
      gradient_at(z, beta, g);
    } else {
      g = g_t;
    }
    phi = alart_curnier(laws_, r, z, g, dim, &lin);
    psi = E * z - e;
  }
  // Not converged: the caller falls back or reports; the state holds the last iterate.
  zc = z;
  project_feasible(laws_, dim, zc);
  gradient_at(zc, beta, gc);
  finish_state(zc, gc);
  return summary;
}

}  // namespace frictopt::contact
