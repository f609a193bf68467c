// SPDX-License-Identifier: MIT
#include "frictopt/contact/working_set_coulomb.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <span>
#include <vector>

#include "frictopt/core/error.hpp"

namespace frictopt::contact {
namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
// A hard cap on the rounds: each adds at least one node, so the loop ends anyway; the cap only
// bounds pathological growth (then the full set is solved in the next round).
constexpr int kMaxRoundsBeforeFullSet = 20;
std::string fmt_seconds(double t) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g s", t);
  return buffer;
}
}  // namespace

WorkingSetCoulombSolver::WorkingSetCoulombSolver(const DelassusMatrix& delassus, const FrictionLaw& law,
                                                 CoulombSolver::Options options)
    : delassus_(delassus), law_(law), options_(std::move(options)) {
  options_.validate();
  if (delassus_.size() % law_.dim() != 0)
    throw InvalidInput("WorkingSetCoulombSolver: delassus size = " + std::to_string(delassus_.size()) +
                       "; expected a multiple of dim = " + std::to_string(law_.dim()));
}

WorkingSetCoulombSolver::Summary WorkingSetCoulombSolver::solve(const Eigen::Ref<const Eigen::VectorXd>& c,
                                                                ContactState& state) const {
  const auto start = std::chrono::steady_clock::now();
  const int dim = law_.dim();
  const Eigen::Index m = delassus_.size(), p = m / dim;
  if (c.size() != m)
    throw InvalidInput("WorkingSetCoulombSolver::solve: c has size " + std::to_string(c.size()) + "; expected " +
                       std::to_string(m));
  if (!c.allFinite()) throw InvalidInput("WorkingSetCoulombSolver::solve: c has non-finite entries");
  const bool warm = state.z.size() == m && state.dim == dim;
  std::vector<char> in_set(static_cast<std::size_t>(p), 0);
  for (Eigen::Index i = 0; i < p; ++i)
    in_set[static_cast<std::size_t>(i)] = c(dim * i + dim - 1) < 0.0 || (warm && state.lambda(i) > 0.0);

  Summary out;
  CoulombSolver::Summary& total = out.coulomb;
  total.method_given = options_.method;
  total.method_used = options_.method == CoulombMethod::kSemismoothNewton ? CoulombMethod::kSemismoothNewton
                                                                         : CoulombMethod::kFixedPoint;
  Eigen::VectorXd z = Eigen::VectorXd::Zero(m), g = c;
  const double c_norm = c.norm();
  const double tolerance = 0.5 * options_.tresca.relative_tolerance * c_norm;
  total.status = Status::kConverged;
  total.message = "no node penetrates the foundation without contact forces";
  for (int round = 1;; ++round) {
    std::vector<Eigen::Index> nodes, unknowns;
    for (Eigen::Index i = 0; i < p; ++i)
      if (in_set[static_cast<std::size_t>(i)]) {
        nodes.push_back(i);
        for (int k = 0; k < dim; ++k) unknowns.push_back(dim * i + k);
      }
    if (round == 1) out.initial_nodes = static_cast<Eigen::Index>(nodes.size());
    out.final_nodes = static_cast<Eigen::Index>(nodes.size());
    out.rounds = round;
    if (!nodes.empty()) {
      auto t = std::chrono::steady_clock::now();
      const DenseDelassus block(delassus_.principal_block(unknowns));
      out.block_seconds += seconds_since(t);
      const Eigen::Index w = static_cast<Eigen::Index>(unknowns.size());
      Eigen::VectorXd c_w(w);
      ContactState sub;
      if (warm || round > 1) {
        sub = ContactState(dim, static_cast<Eigen::Index>(nodes.size()));
        const Eigen::VectorXd& from = round > 1 ? z : state.z;
        for (Eigen::Index k = 0; k < w; ++k) sub.z(k) = from(unknowns[static_cast<std::size_t>(k)]);
        if (!warm && round > 1 && sub.z.isZero(0.0)) sub = ContactState();
      }
      for (Eigen::Index k = 0; k < w; ++k) c_w(k) = c(unknowns[static_cast<std::size_t>(k)]);
      // kAutomatic decides on the size of the whole problem (its contact unknowns), the budget
      // of products on the block's (docs/contact.md, "Semismooth Newton").
      CoulombSolver::Options block_options = options_;
      if (m >= options_.newton.automatic_min_unknowns) block_options.newton.automatic_min_unknowns = 0;
      const CoulombSolver coulomb(block, law_, block_options);
      const CoulombSolver::Summary s = coulomb.solve(c_w, sub);
      total.iterations += s.iterations;
      total.qp_iterations += s.qp_iterations;
      total.operator_applications += s.operator_applications;
      total.inner_not_converged += s.inner_not_converged;
      total.last_relative_increment = s.last_relative_increment;
      total.method_used = s.method_used;
      // Outside W, z = 0 with non-negative gaps adds nothing to it once the rounds end.
      total.relative_projected_gradient = s.relative_projected_gradient;
      total.newton_iterations += s.newton_iterations;
      total.linear_iterations += s.linear_iterations;
      total.factorizations += s.factorizations;
      total.fallback = total.fallback || s.fallback;
      total.status = s.status;
      total.message = s.message;
      z.setZero();
      for (Eigen::Index k = 0; k < w; ++k) z(unknowns[static_cast<std::size_t>(k)]) = sub.z(k);
      t = std::chrono::steady_clock::now();
      delassus_.apply(z, g);
      g += c;
      out.check_seconds += seconds_since(t);
      if (!s.converged()) break;
    }
    // Gaps outside W: nodes that would penetrate join the set.
    double violation2 = 0.0;
    std::vector<Eigen::Index> joining;
    for (Eigen::Index i = 0; i < p; ++i) {
      const double gap = g(dim * i + dim - 1);
      if (in_set[static_cast<std::size_t>(i)] || gap >= 0.0) continue;
      violation2 += gap * gap;
      joining.push_back(i);
    }
    if (std::sqrt(violation2) <= tolerance) break;
    if (round >= kMaxRoundsBeforeFullSet) std::fill(in_set.begin(), in_set.end(), 1);
    for (const Eigen::Index i : joining) in_set[static_cast<std::size_t>(i)] = 1;
  }
  // The block M[W, W] stays for the adjoint; the columns L⁻¹E_W were needed only to grow W.
  delassus_.release_block_columns();
  // The full problem's state and Coulomb residuals (s = λ), as CoulombSolver::solve reports them.
  state = ContactState(dim, p);
  state.z = z;
  state.gradient = g;
  state.slip_bound = state.normal_forces();
  const double c_scale = m ? c.cwiseAbs().maxCoeff() : 0.0;
  const std::span<const FrictionLaw> laws(&law_, 1);
  const ContactResiduals res = contact_residuals(laws, state.slip_bound, state.z, state.gradient, dim, c_scale);
  total.kkt_residual = res.kkt_residual;
  total.complementarity_gap = res.complementarity_gap;
  classify_nodes(state, laws, options_.tresca.classification_tolerance, c_scale);
  total.message += "; working set " + std::to_string(out.final_nodes) + " of " + std::to_string(p) + " nodes (" +
                   std::to_string(out.rounds) + " round" + (out.rounds > 1 ? "s" : "") + ", first " +
                   std::to_string(out.initial_nodes) + "), M[W, W] " + fmt_seconds(out.block_seconds) +
                   ", gap checks " + fmt_seconds(out.check_seconds);
  total.time_seconds = seconds_since(start);
  return out;
}

}  // namespace frictopt::contact
