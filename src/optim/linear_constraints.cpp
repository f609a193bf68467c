// SPDX-License-Identifier: MIT
#include "frictopt/optim/linear_constraints.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "frictopt/core/error.hpp"
#include "frictopt/optim/dense_qp.hpp"

namespace frictopt::optim {


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
