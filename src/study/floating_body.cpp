// SPDX-License-Identifier: MIT
#include "frictopt/study/floating_body.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "frictopt/core/error.hpp"

namespace frictopt::study {

Eigen::MatrixXd rigid_body_modes(const Eigen::Ref<const Eigen::MatrixXd>& X) {
  const Eigen::Index n = X.rows();
  const int dim = static_cast<int>(X.cols());
  const Eigen::RowVectorXd centre = X.colwise().mean();
  const int modes = dim == 3 ? 6 : 3;
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(dim * n, modes);
  for (Eigen::Index a = 0; a < n; ++a) {
    const Eigen::RowVectorXd x = X.row(a) - centre;
    for (int c = 0; c < dim; ++c) R(dim * a + c, c) = 1.0;
    if (dim == 2) {
      R(2 * a, 2) = -x(1);
      R(2 * a + 1, 2) = x(0);
    } else {
      // e_k × x for the axes k = 0, 1, 2.
      R(3 * a + 1, 3) = -x(2), R(3 * a + 2, 3) = x(1);
      R(3 * a + 0, 4) = x(2), R(3 * a + 2, 4) = -x(0);
      R(3 * a + 0, 5) = -x(1), R(3 * a + 1, 5) = x(0);
    }
  }
  return R;
}

Eigen::MatrixXd free_rigid_modes(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                 const std::vector<int>& prescribed_dofs,
                                 const std::vector<std::vector<int>>& ties) {
  const Eigen::MatrixXd R0 = rigid_body_modes(X);
  Eigen::MatrixXd K;
  Eigen::Index tie_rows = 0;
  for (const auto& group : ties) tie_rows += std::max<Eigen::Index>(0, static_cast<Eigen::Index>(group.size()) - 1);
  if (prescribed_dofs.empty() && tie_rows == 0) {
    K = Eigen::MatrixXd::Identity(R0.cols(), R0.cols());
  } else {
    Eigen::MatrixXd Rd(static_cast<Eigen::Index>(prescribed_dofs.size()) + tie_rows, R0.cols());
    for (std::size_t i = 0; i < prescribed_dofs.size(); ++i)
      Rd.row(static_cast<Eigen::Index>(i)) = R0.row(prescribed_dofs[i]);
    // A tied group moves as one: the mode's differences over the group vanish (a plate admits
    // translations, no rotation that turns it).
    Eigen::Index row = static_cast<Eigen::Index>(prescribed_dofs.size());
    for (const auto& group : ties)
      for (std::size_t k = 1; k < group.size(); ++k) Rd.row(row++) = R0.row(group[k]) - R0.row(group[0]);
    // The kernel of the prescribed rows, relative to their scale (a rank decision on a
    // (#prescribed × 6) matrix of coordinates: 1e-10 is far below any body's aspect ratio).
    Eigen::FullPivLU<Eigen::MatrixXd> lu(Rd);
    lu.setThreshold(1e-10);
    K = lu.kernel();
    if (lu.rank() == R0.cols()) K.resize(R0.cols(), 0);
  }
  if (K.cols() == 0) return Eigen::MatrixXd(R0.rows(), 0);
  const Eigen::MatrixXd R = R0 * K;
  // Orthonormal columns (thin Q of a QR), so β and the equality rows are well scaled.
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(R);
  Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(R.rows(), R.cols());
  for (Eigen::Index j = 0; j < Q.cols(); ++j)
    for (int d : prescribed_dofs) Q(d, j) = 0.0;  // exact zeros (round-off of the kernel)
  return Q;
}

bool modes_are_translations(const Eigen::Ref<const Eigen::MatrixXd>& modes, int dim) {
  const Eigen::Index nodes = modes.rows() / dim;
  for (Eigen::Index j = 0; j < modes.cols(); ++j)
    for (Eigen::Index a = 1; a < nodes; ++a)
      for (int c = 0; c < dim; ++c)
        // Relative to the column's scale (orthonormal columns: entries ~ 1/√nodes).
        if (std::abs(modes(a * dim + c, j) - modes(c, j)) > 1e-9 * modes.col(j).cwiseAbs().maxCoeff()) return false;
  return true;
}

std::vector<int> fixing_dofs(const Eigen::Ref<const Eigen::MatrixXd>& modes,
                             const std::vector<int>& prescribed_dofs,
                             const std::vector<int>& excluded_nodes, int dim) {
  const Eigen::Index r = modes.cols();
  std::vector<char> candidate(static_cast<std::size_t>(modes.rows()), 1);
  for (int d : prescribed_dofs) candidate[static_cast<std::size_t>(d)] = 0;
  for (int node : excluded_nodes)
    for (int c = 0; c < dim; ++c) candidate[static_cast<std::size_t>(node * dim + c)] = 0;
  std::vector<int> dofs;
  for (Eigen::Index d = 0; d < modes.rows(); ++d)
    if (candidate[static_cast<std::size_t>(d)]) dofs.push_back(static_cast<int>(d));
  Eigen::MatrixXd rows(r, static_cast<Eigen::Index>(dofs.size()));
  for (std::size_t i = 0; i < dofs.size(); ++i)
    rows.col(static_cast<Eigen::Index>(i)) = modes.row(dofs[i]).transpose();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(rows);
  if (qr.rank() < r)
    throw InvalidInput(
        fmt::format("the body has {} free rigid-body modes but only rank {} among the DOFs off the "
                    "contact surface; expected a body with nodes above its contact surface",
                    r, qr.rank()));
  std::vector<int> chosen;
  for (Eigen::Index j = 0; j < r; ++j)
    chosen.push_back(dofs[static_cast<std::size_t>(qr.colsPermutation().indices()(j))]);
  return chosen;
}

std::string friction_capacity_excess(const contact::FrictionLaw& law,
                                     const Eigen::Vector2d& tangential, double normal, int dim) {
  const double t = tangential.norm();
  if (!(normal > 0.0))
    return fmt::format(
        "no equilibrium: the loads do not press the body onto the foundation (net normal force "
        "{:.6g} N "
        "from the contact would be needed; expected > 0)",
        normal);
  if (t == 0.0) return "";
  const Eigen::Vector2d direction = tangential / t;
  const double mu = law.max_step(Eigen::Vector2d::Zero(), 1.0, direction);
  const double capacity = mu * normal;
  if (t <= capacity) return "";
  const double theta = std::atan2(direction(1), direction(0)) * 180.0 / std::numbers::pi;
  return fmt::format(
      "no equilibrium: the tangential force {:.6g} N {}exceeds the friction capacity μ(θ)·P = "
      "{:.6g} × "
      "{:.6g} N = {:.6g} N by {:.3g} %",
      t, dim == 3 ? fmt::format("at θ = {:.2f}° ", theta) : std::string(), mu, normal, capacity,
      100.0 * (t / capacity - 1.0));
}

}  // namespace frictopt::study
