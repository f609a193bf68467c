// SPDX-License-Identifier: MIT
#include "frictopt/contact/tresca_solver.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "frictopt/core/enum_table.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/core/validation.hpp"

namespace frictopt::contact {
namespace {

constexpr frictopt::detail::EnumTable<TrescaAlgorithm, 3> kAlgorithmNames{{{
    {TrescaAlgorithm::kAutomatic, "automatic"},
    {TrescaAlgorithm::kJointMpgp, "joint_mpgp"},
    {TrescaAlgorithm::kSplit, "split"},
}}};

// A tangential block counts as free (interior) when its boundary offset is below
// −kInteriorRelativeMargin·s·μ_max. After a feasible half-step or a projection the block sits on
// the boundary up to rounding (~1e-16 relative); 1e-12 classifies those as active with a wide
// margin while interior points farther than 1e-12 relative are treated as free.
constexpr double kInteriorRelativeMargin = 1e-12;

enum class Part { kBoth, kTangential, kNormal };

bool has_normal(Part part) { return part != Part::kTangential; }
bool has_tangential(Part part) { return part != Part::kNormal; }

/// MPGP / MPRGP on the dual contact QP restricted to a part of the variables (the others stay
/// fixed). Notation of Dostál (2009), ch. 5, and Dostál–Kozubek (2012): g = ∇ = Mz + c, φ the
/// free gradient, φ̃ the reduced free gradient, β̃ the reduced chopped gradient, ᾱ the fixed
/// step length. The gradient of the *whole* vector is kept up to date, so the fixed part's
/// gradient is correct when the other part is solved next (split variant).
class Engine {
 public:
  Engine(const linalg::LinearOperator& m, const std::vector<FrictionLaw>& laws, int dim,
         const Eigen::VectorXd& s, double alpha_bar, double gamma, TrescaSolver::Summary& summary)
      : m_(m), laws_(laws), dim_(dim), p_(s.size()), s_(s), alpha_bar_(alpha_bar),
        gamma_(gamma), summary_(summary), mx_(m.size()) {}

  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) {
    m_.apply(x, y);
    ++summary_.operator_applications;
  }

  void recompute_gradient(const Eigen::VectorXd& z, const Eigen::VectorXd& c, Eigen::VectorXd& g) {
    apply(z, mx_);
    g = mx_ + c;
  }

  const FrictionLaw& law(Eigen::Index i) const {
    return laws_.size() == 1 ? laws_[0] : laws_[static_cast<std::size_t>(i)];
  }
  Eigen::Vector2d get_t(const Eigen::VectorXd& v, Eigen::Index i) const {
    return dim_ == 3 ? Eigen::Vector2d(v(3 * i), v(3 * i + 1)) : Eigen::Vector2d(v(2 * i), 0.0);
  }
  void set_t(Eigen::VectorXd& v, Eigen::Index i, const Eigen::Vector2d& t) const {
    v(dim_ * i) = t.x();
    if (dim_ == 3) v(3 * i + 1) = t.y();
  }
  Eigen::Index normal_index(Eigen::Index i) const { return dim_ * i + dim_ - 1; }

  /// z ← P(z) on `part`.
  void project(Eigen::VectorXd& z, Part part) const {
    for (Eigen::Index i = 0; i < p_; ++i) {
      if (has_normal(part)) z(normal_index(i)) = std::max(0.0, z(normal_index(i)));
      if (has_tangential(part)) set_t(z, i, law(i).project(get_t(z, i), s_(i)));
    }
  }

  struct Analysis {
    double reduced_gradient_norm2 = 0.0;  // ‖g̃_ᾱ‖² on the part
    double chopped_norm2 = 0.0;           // ‖β̃‖²
    double reduced_free_dot_free = 0.0;   // φ̃ᵀφ
  };

  /// Reduced gradients of Dostál–Kozubek on `part`; fills φ (free gradient) and β (chopped
  /// gradient of the bound blocks, used by MPRGP proportioning) when requested.
  Analysis analyze(const Eigen::VectorXd& z, const Eigen::VectorXd& g, Part part,
                   Eigen::VectorXd* phi, Eigen::VectorXd* beta) const {
    Analysis a;
    if (phi) phi->setZero(z.size());
    if (beta) beta->setZero(z.size());
    for (Eigen::Index i = 0; i < p_; ++i) {
      if (has_normal(part)) {
        const Eigen::Index k = normal_index(i);
        const double lambda = z(k), gk = g(k);
        const double gt = (lambda - std::max(0.0, lambda - alpha_bar_ * gk)) / alpha_bar_;
        a.reduced_gradient_norm2 += gt * gt;
        if (lambda > 0.0) {
          if (phi) (*phi)(k) = gk;
          a.reduced_free_dot_free += gt * gk;
        } else {
          if (beta) (*beta)(k) = gt;  // = min(g, 0)
          a.chopped_norm2 += gt * gt;
        }
      }
      if (has_tangential(part)) {
        const FrictionLaw& w = law(i);
        const double s = s_(i);
        const Eigen::Vector2d q = get_t(z, i), gq = get_t(g, i);
        const Eigen::Vector2d gt = (q - w.project(q - alpha_bar_ * gq, s)) / alpha_bar_;
        a.reduced_gradient_norm2 += gt.squaredNorm();
        const bool free = s > 0.0 && !w.is_zero() &&
                          w.boundary_offset(q, s) < -kInteriorRelativeMargin * s * w.max_coefficient();
        if (free) {
          if (phi) set_t(*phi, i, gq);
          a.reduced_free_dot_free += gt.dot(gq);
        } else {
          a.chopped_norm2 += gt.squaredNorm();
        }
      }
    }
    return a;
  }

  /// Largest α >= 0 with z − α·d feasible (d is zero outside the free blocks of the part).
  double feasible_step(const Eigen::VectorXd& z, const Eigen::VectorXd& d, Part part) const {
    double alpha = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < p_; ++i) {
      if (has_normal(part)) {
        const Eigen::Index k = normal_index(i);
        if (d(k) > 0.0) alpha = std::min(alpha, z(k) / d(k));
      }
      if (has_tangential(part)) {
        const Eigen::Vector2d di = get_t(d, i);
        if (!di.isZero(0.0)) alpha = std::min(alpha, law(i).max_step(get_t(z, i), s_(i), -di));
      }
    }
    return alpha;
  }

  /// Runs MPGP (or MPRGP when only the bound blocks are free to move) on `part` until
  /// ‖g̃_ᾱ‖ <= eps. `budget` counts the remaining QP steps. `g` must equal Mz + c on entry.
  Status run(Eigen::VectorXd& z, Eigen::VectorXd& g, const Eigen::VectorXd& c, Part part,
             double eps, int& budget) {
    const bool mprgp = part == Part::kNormal;
    Eigen::VectorXd phi, beta, d, md(z.size()), trial;
    bool fresh = true;  // g was computed as Mz + c, not by recurrence
    analyze(z, g, part, &d, nullptr);
    while (true) {
      const Analysis a = analyze(z, g, part, &phi, mprgp ? &beta : nullptr);
      if (!std::isfinite(a.reduced_gradient_norm2)) return Status::kNumericalFailure;
      if (std::sqrt(a.reduced_gradient_norm2) <= eps) {
        if (fresh) return Status::kConverged;
        // The recurrence g ← g − αMp drifts; confirm with a fresh gradient and restart CG.
        recompute_gradient(z, c, g);
        fresh = true;
        analyze(z, g, part, &d, nullptr);
        continue;
      }
      if (budget <= 0) return Status::kMaxIterations;
      --budget;
      ++summary_.iterations;
      const double gg2 = gamma_ * gamma_;
      if (a.chopped_norm2 <= gg2 * a.reduced_free_dot_free && a.reduced_free_dot_free > 0.0) {
        // Proportional iterate: a CG step on the free blocks, unless it leaves the set.
        if (d.isZero(0.0)) d = phi;
        apply(d, md);
        const double dmd = d.dot(md);
        if (!(dmd > 0.0)) return Status::kNumericalFailure;  // M not positive definite
        const double alpha_cg = g.dot(d) / dmd;
        const double alpha_f = feasible_step(z, d, part);
        if (alpha_cg <= alpha_f) {
          z -= alpha_cg * d;
          g -= alpha_cg * md;
          fresh = false;
          analyze(z, g, part, &phi, nullptr);
          const double beta_cg = phi.dot(md) / dmd;
          d = phi - beta_cg * d;
          ++summary_.cg_steps;
        } else {
          // Expansion: feasible half-step, then a projected step of fixed length ᾱ
          // (MPRGP: along the free gradient; MPGP: along the full gradient).
          z -= alpha_f * d;
          g -= alpha_f * md;
          if (mprgp) {
            analyze(z, g, part, &phi, nullptr);
            z -= alpha_bar_ * phi;
            project(z, part);
            recompute_gradient(z, c, g);
          } else {
            projected_gradient_step(z, g, c, part, trial);
          }
          fresh = true;
          analyze(z, g, part, &d, nullptr);
          ++summary_.expansion_steps;
        }
      } else {
        // Proportioning: the chopped gradient dominates, release active constraints.
        if (mprgp) {
          apply(beta, md);
          const double bmb = beta.dot(md);
          if (!(bmb > 0.0)) return Status::kNumericalFailure;
          const double alpha = g.dot(beta) / bmb;
          z -= alpha * beta;
          project(z, part);  // exact: β <= 0 only increases λ; guards rounding
          g -= alpha * md;
          fresh = false;
        } else {
          projected_gradient_step(z, g, c, part, trial);
          fresh = true;
        }
        analyze(z, g, part, &d, nullptr);
        ++summary_.proportioning_steps;
      }
    }
  }

  /// z ← P(z − ᾱ g) on `part` (the rest of z unchanged), g ← Mz + c: the MPGP step of fixed
  /// length used by both the expansion and the proportioning step. `trial` is scratch space.
  void projected_gradient_step(Eigen::VectorXd& z, Eigen::VectorXd& g, const Eigen::VectorXd& c, Part part,
                               Eigen::VectorXd& trial) {
    trial = z - alpha_bar_ * g;
    copy_part(trial, z, part);
    project(z, part);
    recompute_gradient(z, c, g);
  }

  double reduced_gradient_norm(const Eigen::VectorXd& z, const Eigen::VectorXd& g,
                               Part part = Part::kBoth) const {
    return std::sqrt(analyze(z, g, part, nullptr, nullptr).reduced_gradient_norm2);
  }

 private:
  void copy_part(const Eigen::VectorXd& from, Eigen::VectorXd& to, Part part) const {
    if (part == Part::kBoth) {
      to = from;
      return;
    }
    for (Eigen::Index i = 0; i < p_; ++i) {
      if (has_normal(part)) to(normal_index(i)) = from(normal_index(i));
      if (has_tangential(part)) set_t(to, i, get_t(from, i));
    }
  }

  const linalg::LinearOperator& m_;
  const std::vector<FrictionLaw>& laws_;
  int dim_;
  Eigen::Index p_;
  const Eigen::VectorXd& s_;
  double alpha_bar_;
  double gamma_;
  TrescaSolver::Summary& summary_;
  Eigen::VectorXd mx_;
};

}  // namespace

std::string_view to_string(TrescaAlgorithm algorithm) { return kAlgorithmNames.name(algorithm); }

TrescaAlgorithm parse_tresca_algorithm(std::string_view text) { return kAlgorithmNames.parse(text, "Tresca algorithm"); }

void TrescaSolver::Options::validate() const {
  const auto fail = [](const char* field, const std::string& value, const char* expected) {
    fail_field("TrescaSolver::Options", field, value, expected);
  };
  if (!(relative_tolerance > 0.0 && relative_tolerance < 1.0))
    fail("relative_tolerance", format_number(relative_tolerance), "a value in (0, 1)");
  if (max_iterations < 1) fail("max_iterations", std::to_string(max_iterations), ">= 1");
  if (!(proportioning_gamma > 0.0) || !std::isfinite(proportioning_gamma))
    fail("proportioning_gamma", format_number(proportioning_gamma), "a finite value > 0");
  if (!(step_length_factor > 0.0 && step_length_factor <= 2.0))
    fail("step_length_factor", format_number(step_length_factor), "a value in (0, 2]");
  if (norm_estimate_iterations < 1)
    fail("norm_estimate_iterations", std::to_string(norm_estimate_iterations), ">= 1");
  if (!(norm_safety_factor >= 1.0) || !std::isfinite(norm_safety_factor))
    fail("norm_safety_factor", format_number(norm_safety_factor), "a finite value >= 1");
  if (max_split_sweeps < 1) fail("max_split_sweeps", std::to_string(max_split_sweeps), ">= 1");
  if (!(classification_tolerance > 0.0 && classification_tolerance < 1.0))
    fail("classification_tolerance", format_number(classification_tolerance), "a value in (0, 1)");
}

std::string TrescaSolver::Summary::brief_report() const {
  std::ostringstream out;
  out.precision(3);
  out << "Tresca " << to_string(algorithm_used) << ": " << to_string(status) << ", "
      << iterations << " it (cg " << cg_steps << ", exp " << expansion_steps << ", prop "
      << proportioning_steps;
  if (split_sweeps > 0) out << ", sweeps " << split_sweeps;
  out << "), " << operator_applications << " applies, |g~|/|c| " << relative_projected_gradient
      << ", KKT " << kkt_residual << ", gap " << complementarity_gap << ", " << time_seconds
      << " s";
  return out.str();
}

TrescaSolver::TrescaSolver(const linalg::LinearOperator& delassus, const FrictionLaw& law, Options options)
    : TrescaSolver(delassus, std::vector<FrictionLaw>{law}, std::move(options)) {}

TrescaSolver::TrescaSolver(const linalg::LinearOperator& delassus, const FrictionLaw& law)
    : TrescaSolver(delassus, std::vector<FrictionLaw>{law}, Options{}) {}

TrescaSolver::TrescaSolver(const linalg::LinearOperator& delassus, std::vector<FrictionLaw> laws,
                           Options options)
    : delassus_(delassus), laws_(std::move(laws)), options_(std::move(options)) {
  options_.validate();
  if (laws_.empty()) throw InvalidInput("TrescaSolver: laws is empty; expected 1 or p laws");
  dim_ = laws_.front().dim();
  for (std::size_t i = 0; i < laws_.size(); ++i)
    if (laws_[i].dim() != dim_)
      throw InvalidInput("TrescaSolver: laws[" + std::to_string(i) + "] is " + laws_[i].describe() +
                         " of dimension " + std::to_string(laws_[i].dim()) + "; expected dimension " +
                         std::to_string(dim_) + " like laws[0]");
  const Eigen::Index n = delassus_.size();
  if (n % dim_ != 0)
    throw InvalidInput("TrescaSolver: delassus size = " + std::to_string(n) +
                       "; expected a multiple of dim = " + std::to_string(dim_));
  num_nodes_ = n / dim_;
  if (laws_.size() != 1 && static_cast<Eigen::Index>(laws_.size()) != num_nodes_)
    throw InvalidInput("TrescaSolver: laws.size() = " + std::to_string(laws_.size()) +
                       "; expected 1 or the number of nodes " + std::to_string(num_nodes_));
  if (n == 0) {
    norm_estimate_ = 0.0;
    alpha_bar_ = 1.0;
    return;
  }
  // Power iteration from a fixed start vector with no symmetry, so it is not orthogonal to the
  // dominant eigenvector of structured operators; ‖Mv‖ for unit v is a lower bound of ‖M‖.
  Eigen::VectorXd v(n), w(n);
  for (Eigen::Index k = 0; k < n; ++k) v(k) = 1.0 + 0.5 * std::sin(1.0 + 0.7 * static_cast<double>(k));
  v.normalize();
  double estimate = 0.0;
  for (int it = 0; it < options_.norm_estimate_iterations; ++it) {
    delassus_.apply(v, w);
    estimate = w.norm();
    if (!(estimate > 0.0) || !std::isfinite(estimate))
      throw InvalidInput("TrescaSolver: power iteration on the Delassus operator gave ‖Mv‖ = " +
                         format_number(estimate) + "; expected a finite SPD operator");
    v = w / estimate;
  }
  norm_estimate_ = options_.norm_safety_factor * estimate;
  alpha_bar_ = options_.step_length_factor / norm_estimate_;
}

TrescaSolver::Summary TrescaSolver::solve(const Eigen::Ref<const Eigen::VectorXd>& c,
                                          const Eigen::Ref<const Eigen::VectorXd>& slip_bound,
                                          ContactState& state) const {
  return solve_impl(c, slip_bound, state, options_.relative_tolerance, static_cast<int>(Part::kBoth));
}

TrescaSolver::Summary TrescaSolver::solve_to(const Eigen::Ref<const Eigen::VectorXd>& c,
                                             const Eigen::Ref<const Eigen::VectorXd>& slip_bound,
                                             ContactState& state, double relative_tolerance) const {
  if (!(relative_tolerance > 0.0 && relative_tolerance < 1.0))
    throw InvalidInput("TrescaSolver::solve_to: relative_tolerance = " + format_number(relative_tolerance) +
                       "; expected a value in (0, 1)");
  return solve_impl(c, slip_bound, state, relative_tolerance, static_cast<int>(Part::kBoth));
}

TrescaSolver::Summary TrescaSolver::solve_block(Block block,
                                                const Eigen::Ref<const Eigen::VectorXd>& c,
                                                const Eigen::Ref<const Eigen::VectorXd>& slip_bound,
                                                ContactState& state,
                                                double relative_tolerance) const {
  if (!(relative_tolerance > 0.0 && relative_tolerance < 1.0))
    throw InvalidInput("TrescaSolver::solve_block: relative_tolerance = " +
                       format_number(relative_tolerance) + "; expected a value in (0, 1)");
  if (state.z.size() != delassus_.size() || state.dim != dim_)
    throw InvalidInput("TrescaSolver::solve_block: state.z has size " +
                       std::to_string(state.z.size()) + "; expected " +
                       std::to_string(delassus_.size()) + " (the fixed block is read from it)");
  const Part part = block == Block::kTangential ? Part::kTangential : Part::kNormal;
  return solve_impl(c, slip_bound, state, relative_tolerance, static_cast<int>(part));
}

TrescaSolver::Summary TrescaSolver::solve_impl(const Eigen::Ref<const Eigen::VectorXd>& c,
                                               const Eigen::Ref<const Eigen::VectorXd>& slip_bound,
                                               ContactState& state, double relative_tolerance,
                                               int part_code) const {
  const Part part = static_cast<Part>(part_code);
  const auto start = std::chrono::steady_clock::now();
  const Eigen::Index n = delassus_.size();
  if (c.size() != n)
    throw InvalidInput("TrescaSolver::solve: c has size " + std::to_string(c.size()) +
                       "; expected " + std::to_string(n));
  if (!c.allFinite()) throw InvalidInput("TrescaSolver::solve: c has non-finite entries");
  if (slip_bound.size() != num_nodes_)
    throw InvalidInput("TrescaSolver::solve: slip_bound has size " +
                       std::to_string(slip_bound.size()) + "; expected " +
                       std::to_string(num_nodes_));
  for (Eigen::Index i = 0; i < num_nodes_; ++i)
    if (!(slip_bound(i) >= 0.0) || !std::isfinite(slip_bound(i)))
      throw InvalidInput("TrescaSolver::solve: slip_bound[" + std::to_string(i) + "] = " +
                         format_number(slip_bound(i)) + "; expected a finite value >= 0");

  Summary summary;
  summary.algorithm_given = options_.algorithm;
  summary.algorithm_used = options_.algorithm == TrescaAlgorithm::kAutomatic
                               ? TrescaAlgorithm::kJointMpgp
                               : options_.algorithm;
  const Eigen::VectorXd s = slip_bound;
  const Eigen::VectorXd cc = c;
  Engine engine(delassus_, laws_, dim_, s, alpha_bar_, options_.proportioning_gamma, summary);

  Eigen::VectorXd z = state.z.size() == n && state.dim == dim_ ? Eigen::VectorXd(state.z)
                                                                : Eigen::VectorXd::Zero(n);
  const double c_norm = cc.norm();
  Eigen::VectorXd g(n);
  if (c_norm == 0.0 && part == Part::kBoth) {
    // ½zᵀMz is minimized by z = 0, which is feasible.
    z.setZero();
    g.setZero();
    summary.status = Status::kConverged;
  } else {
    engine.project(z, part);
    engine.recompute_gradient(z, cc, g);
    const double eps = relative_tolerance * c_norm;
    int budget = options_.max_iterations;
    if (part != Part::kBoth) {
      summary.algorithm_used = TrescaAlgorithm::kSplit;
      summary.status = engine.run(z, g, cc, part, eps, budget);
    } else if (summary.algorithm_used == TrescaAlgorithm::kJointMpgp) {
      summary.status = engine.run(z, g, cc, Part::kBoth, eps, budget);
    } else {
      // Block Gauss–Seidel (docs/theory/state-problem.md §6, steps I/II): each block is solved to a
      // tolerance a tenth of the current joint residual (but not below half the final one), so that
      // inner accuracy follows the outer progress. The joint reduced gradient is the concatenation
      // of the two blocks', so at least one block has work in every sweep.
      summary.status = Status::kMaxIterations;
      while (true) {
        const double r = engine.reduced_gradient_norm(z, g);
        if (!std::isfinite(r)) {
          summary.status = Status::kNumericalFailure;
          break;
        }
        if (r <= eps) {
          summary.status = Status::kConverged;
          break;
        }
        if (summary.split_sweeps >= options_.max_split_sweeps || budget <= 0) break;
        const double eps_inner = std::max(0.5 * eps, 0.1 * r);
        ++summary.split_sweeps;
        Status st = engine.run(z, g, cc, Part::kTangential, eps_inner, budget);
        if (st == Status::kConverged) st = engine.run(z, g, cc, Part::kNormal, eps_inner, budget);
        if (st == Status::kNumericalFailure) {
          summary.status = st;
          break;
        }
        engine.recompute_gradient(z, cc, g);
      }
    }
    engine.recompute_gradient(z, cc, g);
    summary.relative_projected_gradient =
        c_norm > 0.0 ? engine.reduced_gradient_norm(z, g, part) / c_norm : 0.0;
  }
  switch (summary.status) {
    case Status::kConverged:
      summary.message = "relative projected gradient " + format_number(summary.relative_projected_gradient) +
                        " <= " + format_number(relative_tolerance);
      break;
    case Status::kMaxIterations:
      summary.message = "iteration limit reached (max_iterations = " +
                        std::to_string(options_.max_iterations) + ", max_split_sweeps = " +
                        std::to_string(options_.max_split_sweeps) + ")";
      break;
    default:
      summary.message = "non-finite values or a non-positive curvature pᵀMp: the Delassus "
                        "operator is not SPD or the data are not finite";
  }
  const ContactResiduals res = contact_residuals(laws_, s, z, g, dim_, (cc.size() ? cc.cwiseAbs().maxCoeff() : 0.0));
  summary.kkt_residual = res.kkt_residual;
  summary.complementarity_gap = res.complementarity_gap;
  summary.objective = 0.5 * z.dot(g + cc);
  state.dim = dim_;
  state.z = std::move(z);
  state.gradient = std::move(g);
  state.slip_bound = s;
  classify_nodes(state, laws_, options_.classification_tolerance, (cc.size() ? cc.cwiseAbs().maxCoeff() : 0.0));
  summary.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace frictopt::contact
