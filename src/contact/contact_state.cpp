// SPDX-License-Identifier: MIT
#include "frictopt/contact/contact_state.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "frictopt/core/enum_table.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::contact {
namespace {

constexpr frictopt::detail::EnumTable<NodeStatus, 3> kNodeStatusNames{{{
    {NodeStatus::kSeparated, "separated"},
    {NodeStatus::kStick, "stick"},
    {NodeStatus::kSlip, "slip"},
}}};

// Floor of the solution scales Λ and U: far below any physical force or displacement, above
// denormals, so that an all-zero state has finite (and zero) residuals.
constexpr double kTiny = 1e-300;

const FrictionLaw& law_of(std::span<const FrictionLaw> laws, Eigen::Index i) {
  return laws.size() == 1 ? laws[0] : laws[static_cast<std::size_t>(i)];
}

Eigen::Vector2d tangential(const Eigen::Ref<const Eigen::VectorXd>& v, int dim, Eigen::Index i) {
  return dim == 3 ? Eigen::Vector2d(v(3 * i), v(3 * i + 1)) : Eigen::Vector2d(v(2 * i), 0.0);
}

}  // namespace

std::string_view to_string(NodeStatus status) { return kNodeStatusNames.name(status); }

NodeStatus parse_node_status(std::string_view text) { return kNodeStatusNames.parse(text, "node status"); }

ContactState::ContactState(int dimension, Eigen::Index num_nodes)
    : dim(dimension),
      z(Eigen::VectorXd::Zero(dimension * num_nodes)),
      gradient(Eigen::VectorXd::Zero(dimension * num_nodes)),
      slip_bound(Eigen::VectorXd::Zero(num_nodes)) {
  if (dimension != 2 && dimension != 3)
    throw InvalidInput("ContactState: dim = " + std::to_string(dimension) + "; expected 2 or 3");
}

Eigen::Vector2d ContactState::q(Eigen::Index i) const { return tangential(z, dim, i); }
Eigen::Vector2d ContactState::u_t(Eigen::Index i) const { return -tangential(gradient, dim, i); }

Eigen::VectorXd ContactState::normal_forces() const {
  Eigen::VectorXd lambda(num_nodes());
  for (Eigen::Index i = 0; i < num_nodes(); ++i) lambda(i) = this->lambda(i);
  return lambda;
}

void classify_nodes(ContactState& state, std::span<const FrictionLaw> laws,
                    double relative_tolerance, double c_scale) {
  const Eigen::Index p = state.num_nodes();
  FRICTOPT_ASSERT(laws.size() == 1 || static_cast<Eigen::Index>(laws.size()) == p,
                  "classify_nodes: laws must have 1 or p entries");
  double force_scale = kTiny, disp_scale = std::max(kTiny, c_scale);
  for (Eigen::Index i = 0; i < p; ++i) {
    force_scale = std::max({force_scale, state.lambda(i), state.q(i).norm()});
    disp_scale = std::max({disp_scale, state.u_t(i).norm(), std::abs(state.normal_gap(i))});
  }
  const double tau_force = relative_tolerance * force_scale;
  const double tau_disp = relative_tolerance * disp_scale;
  state.scales = {tau_force, tau_disp};
  state.nodes.assign(static_cast<std::size_t>(p), NodeClassification{});
  for (Eigen::Index i = 0; i < p; ++i) {
    auto& node = state.nodes[static_cast<std::size_t>(i)];
    const Eigen::Vector2d u = state.u_t(i);
    const double nu = u.norm();
    const double s = state.slip_bound.size() == p ? state.slip_bound(i) : state.lambda(i);
    const ClassificationTolerance tol{tau_force, tau_disp,
                                      std::max(relative_tolerance, nu > 0 ? tau_disp / nu : 1.0)};
    node.faces = law_of(laws, i).classify(state.q(i), s, u, tol);
    if (state.lambda(i) <= tau_force) {
      node.status = NodeStatus::kSeparated;
    } else if (nu <= tau_disp) {
      node.status = NodeStatus::kStick;
    } else {
      node.status = NodeStatus::kSlip;
      node.slip_direction = u / nu;
    }
  }
}

ContactResiduals contact_residuals(std::span<const FrictionLaw> laws,
                                   const Eigen::Ref<const Eigen::VectorXd>& slip_bound,
                                   const Eigen::Ref<const Eigen::VectorXd>& z,
                                   const Eigen::Ref<const Eigen::VectorXd>& gradient, int dim,
                                   double c_scale) {
  const Eigen::Index p = z.size() / dim;
  FRICTOPT_ASSERT(gradient.size() == z.size() && slip_bound.size() == p,
                  "contact_residuals: size mismatch");
  ContactResiduals r;
  if (p == 0) return r;
  const double lambda_scale = std::max(kTiny, z.cwiseAbs().maxCoeff());
  const double u_scale = std::max({kTiny, gradient.cwiseAbs().maxCoeff(), c_scale});
  const double step = lambda_scale / u_scale;
  for (Eigen::Index i = 0; i < p; ++i) {
    const FrictionLaw& law = law_of(laws, i);
    const double s = std::max(0.0, slip_bound(i));
    const double lambda = z(dim * i + dim - 1), w = gradient(dim * i + dim - 1);
    const Eigen::Vector2d q = tangential(z, dim, i), g_q = tangential(gradient, dim, i);
    const double r_normal = lambda - std::max(0.0, lambda - step * w);
    const Eigen::Vector2d r_tangential = q - law.project(q - step * g_q, s);
    r.kkt_residual = std::max(
        r.kkt_residual, std::sqrt(r_normal * r_normal + r_tangential.squaredNorm()) / lambda_scale);
    const Eigen::Vector2d u = -g_q;
    const double gap = std::abs(lambda) * std::abs(w) + std::abs(s * law.support(u) - q.dot(u));
    r.complementarity_gap = std::max(r.complementarity_gap, gap / (lambda_scale * u_scale));
  }
  return r;
}

}  // namespace frictopt::contact
