// SPDX-License-Identifier: MIT
#include "frictopt/optim/linear_constraints.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "frictopt/core/error.hpp"
#include "frictopt/optim/dense_qp.hpp"

namespace frictopt::optim {

namespace {
std::string dims(Eigen::Index r, Eigen::Index c) {
  std::ostringstream s;
  s << r << "x" << c;
  return s.str();
}
}  // namespace

bool LinearConstraints::empty() const {
  const bool no_lower = lower.size() == 0 || (lower.array() == -std::numeric_limits<double>::infinity()).all();
  const bool no_upper = upper.size() == 0 || (upper.array() == std::numeric_limits<double>::infinity()).all();
  return no_lower && no_upper && A_in.rows() == 0 && A_eq.rows() == 0;
}

void LinearConstraints::validate(Eigen::Index n) const {
  const std::string nn = std::to_string(n);
  if (lower.size() != 0 && lower.size() != n)
    throw InvalidInput("LinearConstraints::lower has size " + std::to_string(lower.size()) +
                       "; expected 0 or n = " + nn);
  if (upper.size() != 0 && upper.size() != n)
    throw InvalidInput("LinearConstraints::upper has size " + std::to_string(upper.size()) +
                       "; expected 0 or n = " + nn);
  for (Eigen::Index i = 0; i < lower.size(); ++i) {
    if (std::isnan(lower(i)) || lower(i) == std::numeric_limits<double>::infinity())
      throw InvalidInput("LinearConstraints::lower[" + std::to_string(i) + "] = " +
                         std::to_string(lower(i)) + "; expected a finite number or -inf");
  }
  for (Eigen::Index i = 0; i < upper.size(); ++i) {
    if (std::isnan(upper(i)) || upper(i) == -std::numeric_limits<double>::infinity())
      throw InvalidInput("LinearConstraints::upper[" + std::to_string(i) + "] = " +
                         std::to_string(upper(i)) + "; expected a finite number or +inf");
    if (lower.size() == n && lower(i) > upper(i))
      throw InvalidInput("LinearConstraints: lower[" + std::to_string(i) + "] = " +
                         std::to_string(lower(i)) + " > upper[" + std::to_string(i) + "] = " +
                         std::to_string(upper(i)) + "; expected lower <= upper (empty box)");
  }
  if (A_in.rows() > 0 && A_in.cols() != n)
    throw InvalidInput("LinearConstraints::A_in is " + dims(A_in.rows(), A_in.cols()) +
                       "; expected m x " + nn);
  if (b_in.size() != A_in.rows())
    throw InvalidInput("LinearConstraints::b_in has size " + std::to_string(b_in.size()) +
                       "; expected A_in.rows() = " + std::to_string(A_in.rows()));
  if (A_eq.rows() > 0 && A_eq.cols() != n)
    throw InvalidInput("LinearConstraints::A_eq is " + dims(A_eq.rows(), A_eq.cols()) +
                       "; expected p x " + nn);
  if (b_eq.size() != A_eq.rows())
    throw InvalidInput("LinearConstraints::b_eq has size " + std::to_string(b_eq.size()) +
                       "; expected A_eq.rows() = " + std::to_string(A_eq.rows()));
  if (!A_in.allFinite() || !b_in.allFinite() || !A_eq.allFinite() || !b_eq.allFinite())
    throw InvalidInput("LinearConstraints: non-finite entry in A_in, b_in, A_eq or b_eq; expected finite numbers");
}

double LinearConstraints::max_violation(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  double v = 0.0;
  for (Eigen::Index i = 0; i < lower.size(); ++i) v = std::max(v, lower(i) - x(i));
  for (Eigen::Index i = 0; i < upper.size(); ++i) v = std::max(v, x(i) - upper(i));
  if (A_in.rows() > 0) v = std::max(v, (A_in * x - b_in).maxCoeff());
  if (A_eq.rows() > 0) v = std::max(v, (A_eq * x - b_eq).lpNorm<Eigen::Infinity>());
  return v;
}

GeneralForm to_general_form(const LinearConstraints& k, Eigen::Index n) {
  k.validate(n);
  GeneralForm out;
  std::vector<Eigen::VectorXd> rows;
  std::vector<double> rhs;
  for (Eigen::Index i = 0; i < k.lower.size(); ++i) {
    if (std::isfinite(k.lower(i))) {
      rows.push_back(-Eigen::VectorXd::Unit(n, i));
      rhs.push_back(-k.lower(i));
      out.row_origin.push_back("lower[" + std::to_string(i) + "]");
    }
  }
  for (Eigen::Index i = 0; i < k.upper.size(); ++i) {
    if (std::isfinite(k.upper(i))) {
      rows.push_back(Eigen::VectorXd::Unit(n, i));
      rhs.push_back(k.upper(i));
      out.row_origin.push_back("upper[" + std::to_string(i) + "]");
    }
  }
  for (Eigen::Index i = 0; i < k.A_in.rows(); ++i) {
    rows.push_back(k.A_in.row(i).transpose());
    rhs.push_back(k.b_in(i));
    out.row_origin.push_back("A_in[" + std::to_string(i) + "]");
  }
  out.C.resize(static_cast<Eigen::Index>(rows.size()), n);
  out.c.resize(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    out.C.row(static_cast<Eigen::Index>(r)) = rows[r].transpose();
    out.c(static_cast<Eigen::Index>(r)) = rhs[r];
  }
  out.E = k.A_eq.rows() > 0 ? k.A_eq : Eigen::MatrixXd(0, n);
  out.e = k.b_eq;
  return out;
}

Projection project_onto(const LinearConstraints& constraints,
                        const Eigen::Ref<const Eigen::VectorXd>& x) {
  const Eigen::Index n = x.size();
  const GeneralForm gf = to_general_form(constraints, n);
  Projection out;
  QpProblem qp;
  qp.H = Eigen::MatrixXd::Identity(n, n);
  qp.g = -x;
  qp.A_in = gf.C;
  qp.b_in = gf.c;
  qp.A_eq = gf.E;
  qp.b_eq = gf.e;
  const DenseQpSolver solver;
  const DenseQpSolver::Summary s = solver.solve(qp);
  if (s.outcome == QpOutcome::kInfeasible) {
    out.feasible_set_empty = true;
    out.message = s.message;
    out.point = x;
    out.distance = kNaN;
    return out;
  }
  if (!s.converged()) {
    out.converged = false;
    out.message = "projection QP did not converge: " + s.brief_report();
    out.point = s.x;
    out.distance = (s.x - x).norm();
    return out;
  }
  out.point = s.x;
  out.distance = (s.x - x).norm();
  return out;
}

}  // namespace frictopt::optim
