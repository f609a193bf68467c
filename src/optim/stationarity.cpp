// SPDX-License-Identifier: MIT
#include "frictopt/optim/stationarity.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "frictopt/core/error.hpp"
#include "frictopt/optim/dense_qp.hpp"

namespace frictopt::optim {

void StationarityOptions::validate() const {
  if (!(active_tolerance >= 0.0))
    throw InvalidInput("StationarityOptions::active_tolerance = " + std::to_string(active_tolerance) +
                       "; expected >= 0");
  if (!(duplicate_tolerance >= 0.0))
    throw InvalidInput("StationarityOptions::duplicate_tolerance = " +
                       std::to_string(duplicate_tolerance) + "; expected >= 0");
}

std::string StationarityCertificate::brief_report() const {
  std::ostringstream s;
  s << "Stationarity: " << to_string(status) << ", distance " << distance << " (scale "
    << subgradient_scale << "), " << num_distinct_subgradients << " distinct subgradients, "
    << active_inequalities.size() << " active inequalities";
  if (!message.empty()) s << " — " << message;
  return s.str();
}

std::vector<Eigen::Index> distinct_columns(const Eigen::Ref<const Eigen::MatrixXd>& Xi, double tolerance,
                                           std::vector<Eigen::Index>& group) {
  const double threshold = tolerance * Xi.cwiseAbs().maxCoeff();  // all-zero Xi: one group
  std::vector<Eigen::Index> rep;
  group.assign(static_cast<std::size_t>(Xi.cols()), -1);
  for (Eigen::Index j = 0; j < Xi.cols(); ++j) {
    for (std::size_t r = 0; r < rep.size(); ++r)
      if ((Xi.col(j) - Xi.col(rep[r])).lpNorm<Eigen::Infinity>() <= threshold) {
        group[static_cast<std::size_t>(j)] = static_cast<Eigen::Index>(r);
        break;
      }
    if (group[static_cast<std::size_t>(j)] < 0) {
      group[static_cast<std::size_t>(j)] = static_cast<Eigen::Index>(rep.size());
      rep.push_back(j);
    }
  }
  return rep;
}

StationarityCertificate stationarity_certificate(const Eigen::Ref<const Eigen::MatrixXd>& Xi,
                                                 const Eigen::Ref<const Eigen::VectorXd>& x,
                                                 const LinearConstraints& constraints,
                                                 const StationarityOptions& options) {
  options.validate();
  const Eigen::Index n = x.size();
  if (Xi.rows() != n || Xi.cols() == 0)
    throw InvalidInput("stationarity_certificate: subgradients is " + std::to_string(Xi.rows()) + "x" +
                       std::to_string(Xi.cols()) + "; expected " + std::to_string(n) +
                       " x m with m >= 1 (one subgradient per column)");
  if (!Xi.allFinite() || !x.allFinite())
    throw InvalidInput("stationarity_certificate: non-finite entry in subgradients or x; expected finite numbers");
  const GeneralForm gf = to_general_form(constraints, n);
  const double viol = constraints.max_violation(x);
  if (viol > options.active_tolerance * std::max(1.0, x.lpNorm<Eigen::Infinity>()))
    throw InvalidInput("stationarity_certificate: x violates the constraints by " + std::to_string(viol) +
                       "; expected a feasible point (N_Υ(x) is defined on Υ only)");

  StationarityCertificate out;
  // Deduplicate: many selections give identical ξ (docs/theory/stationarity.md §2).
  std::vector<Eigen::Index> group;
  const std::vector<Eigen::Index> rep = distinct_columns(Xi, options.duplicate_tolerance, group);
  const auto m = static_cast<Eigen::Index>(rep.size());
  out.num_distinct_subgradients = static_cast<int>(m);
  out.subgradient_scale = Xi.colwise().norm().maxCoeff();

  for (Eigen::Index i = 0; i < gf.C.rows(); ++i) {
    if (gf.c(i) - gf.C.row(i).dot(x) <= options.active_tolerance * std::max(1.0, std::abs(gf.c(i)))) {
      out.active_inequalities.push_back(static_cast<int>(i));
      out.active_names.push_back(gf.row_origin[static_cast<std::size_t>(i)]);
    }
  }
  const auto pa = static_cast<Eigen::Index>(out.active_inequalities.size());
  const Eigen::Index q = gf.E.rows();
  // Variables w = (θ, η, ζ); M w = Ξθ + C_Aᵀη + Eᵀζ; objective ½‖Mw‖² (H = MᵀM, PSD).
  // Scaling: the subgradient columns are divided by S = max‖ξ_i‖ and every
  // constraint normal by its own norm (η, ζ absorb the factors; η ≥ 0 is kept), so H has O(1)
  // entries whatever the units: unscaled, ‖ξ‖ ~ 1e15 next to unit normals left the active-set
  // solver without a usable tolerance. δ = S·min‖M̂ŵ‖.
  const double S = out.subgradient_scale > 0.0 ? out.subgradient_scale : 1.0;
  Eigen::MatrixXd M(n, m + pa + q);
  for (Eigen::Index r = 0; r < m; ++r) M.col(r) = Xi.col(rep[static_cast<std::size_t>(r)]) / S;
  for (Eigen::Index r = 0; r < pa; ++r) {
    const Eigen::VectorXd c = gf.C.row(out.active_inequalities[static_cast<std::size_t>(r)]).transpose();
    M.col(m + r) = c / c.norm();  // rows of the general form are never zero
  }
  for (Eigen::Index r = 0; r < q; ++r) {
    const double nrm = gf.E.row(r).norm();
    M.col(m + pa + r) = nrm > 0.0 ? Eigen::VectorXd(gf.E.row(r).transpose() / nrm) : Eigen::VectorXd::Zero(n);
  }
  QpProblem qp;
  qp.H = M.transpose() * M;
  qp.g = Eigen::VectorXd::Zero(M.cols());
  qp.A_eq = Eigen::MatrixXd::Zero(1, M.cols());
  qp.A_eq.leftCols(m).setOnes();
  qp.b_eq = Eigen::VectorXd::Ones(1);
  qp.A_in = Eigen::MatrixXd::Zero(m + pa, M.cols());
  qp.A_in.topLeftCorner(m + pa, m + pa) = -Eigen::MatrixXd::Identity(m + pa, m + pa);
  qp.b_in = Eigen::VectorXd::Zero(m + pa);
  Eigen::VectorXd start = Eigen::VectorXd::Zero(M.cols());
  // Start at the shortest ξ (θ = e_i): feasible, so no phase one, and already an upper bound.
  Eigen::Index shortest = 0;
  M.leftCols(m).colwise().norm().minCoeff(&shortest);
  start(shortest) = 1.0;
  const DenseQpSolver solver;
  const DenseQpSolver::Summary s = solver.solve(qp, start);
  if (!s.converged() || !s.x.allFinite()) {
    out.status = s.converged() ? Status::kNumericalFailure : s.status;
    out.message = "stationarity QP failed: " + s.brief_report();
    return out;  // distance, weights, parts stay NaN/empty: not a result
  }
  const Eigen::VectorXd w = s.x;
  out.weights = Eigen::VectorXd::Zero(Xi.cols());
  for (Eigen::Index j = 0; j < Xi.cols(); ++j) {
    const Eigen::Index r = group[static_cast<std::size_t>(j)];
    if (rep[static_cast<std::size_t>(r)] == j) out.weights(j) = std::max(0.0, w(r));
  }
  const double weight_sum = out.weights.sum();
  if (!(weight_sum > 0.0) || !std::isfinite(weight_sum)) {
    out.status = Status::kNumericalFailure;
    out.message = "stationarity QP returned weights that do not sum to a positive number (" +
                  std::to_string(weight_sum) + ")";
    out.weights.resize(0);
    return out;
  }
  out.weights /= weight_sum;
  out.subgradient_part = Xi * out.weights;
  out.normal_part = S * (M.rightCols(pa + q) * w.tail(pa + q));
  out.distance = (out.subgradient_part + out.normal_part).norm();
  if (!std::isfinite(out.distance)) {
    out.status = Status::kNumericalFailure;
    out.message = "stationarity distance is not finite";
    out.distance = kNaN;
    return out;
  }
  out.status = Status::kConverged;
  out.message.clear();
  return out;
}

}  // namespace frictopt::optim
