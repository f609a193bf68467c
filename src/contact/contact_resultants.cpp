// SPDX-License-Identifier: MIT
#include "frictopt/contact/contact_resultants.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "frictopt/core/error.hpp"

namespace frictopt::contact {
namespace {

// 3D: radius of the disc of area A; 2D: half-width of the strip of length A.
double equivalent_radius(double area, int dim) {
  return dim == 3 ? std::sqrt(area / std::numbers::pi) : 0.5 * area;
}

}  // namespace

std::string ContactResultants::brief_report() const {
  std::string line = fmt::format("contact forces: P = {:.6e} N, T = ", normal_force);
  line += dim == 3 ? fmt::format("({:.6e}, {:.6e}) N", tangential_force(0), tangential_force(1))
                   : fmt::format("{:.6e} N", tangential_force(0));
  line += fmt::format(
      ", |T|/P = {:.6g}; contact area {:.4e}; stick {} ({:.4e}), slip {} ({:.4e}), separated {}",
      force_ratio, contact_area, num_stick, stick_area, num_slip, slip_area, num_separated);
  if (num_stick > 0) {
    line += dim == 3 ? fmt::format("; stick centroid ({:.4e}, {:.4e}), radius {:.4e}",
                                   stick_centroid(0), stick_centroid(1), stick_equivalent_radius)
                     : fmt::format("; stick centroid {:.4e}, half-width {:.4e}", stick_centroid(0),
                                   stick_equivalent_radius);
  }
  return line;
}

ContactResultants contact_resultants(const ContactState& state,
                                     const Eigen::Ref<const Eigen::VectorXd>& areas,
                                     const Eigen::Ref<const Eigen::MatrixXd>& plane) {
  Eigen::MatrixXd rows = Eigen::MatrixXd::Identity(state.dim, state.dim);
  rows.topLeftCorner(state.dim - 1, state.dim - 1) *= -1.0;
  return contact_resultants(state, areas, plane, rows);
}

ContactResultants contact_resultants(const ContactState& state,
                                     const Eigen::Ref<const Eigen::VectorXd>& areas,
                                     const Eigen::Ref<const Eigen::MatrixXd>& plane,
                                     const Eigen::Ref<const Eigen::MatrixXd>& frame_rows) {
  const Eigen::Index p = state.num_nodes();
  if (areas.size() != p || plane.rows() != p || plane.cols() != state.dim - 1 ||
      static_cast<Eigen::Index>(state.nodes.size()) != p)
    throw InvalidInput(fmt::format(
        "contact_resultants: {} contact nodes but {} areas, {}×{} plane coordinates and {} "
        "classified nodes; "
        "expected {} each (plane: {} columns)",
        p, areas.size(), plane.rows(), plane.cols(), state.nodes.size(), p, state.dim - 1));
  if (frame_rows.rows() != state.dim || frame_rows.cols() != state.dim)
    throw InvalidInput(fmt::format("contact_resultants: frame rows {}×{}; expected {}×{}", frame_rows.rows(),
                                   frame_rows.cols(), state.dim, state.dim));
  ContactResultants r;
  r.dim = state.dim;
  Eigen::Vector2d weighted = Eigen::Vector2d::Zero();
  for (Eigen::Index i = 0; i < p; ++i) {
    r.normal_force += state.lambda(i);
    r.tangential_force -= state.q(i);  // τ_i = −q_i
    const double a = areas(i);
    switch (state.nodes[static_cast<std::size_t>(i)].status) {
      case NodeStatus::kStick: {
        ++r.num_stick;
        r.stick_area += a;
        Eigen::Vector2d x = Eigen::Vector2d::Zero();
        x.head(state.dim - 1) = plane.row(i).transpose();
        weighted += a * x;
        break;
      }
      case NodeStatus::kSlip:
        ++r.num_slip;
        r.slip_area += a;
        break;
      case NodeStatus::kSeparated:
        ++r.num_separated;
        r.separated_area += a;
        break;
    }
  }
  // Σ Fᵀz_i = Fᵀ Σz_i: the force on the body in global axes.
  Eigen::VectorXd total = Eigen::VectorXd::Zero(state.dim);
  for (Eigen::Index i = 0; i < p; ++i) total += state.z.segment(state.dim * i, state.dim);
  r.global_force.head(state.dim) = frame_rows.transpose() * total;
  r.tangential_force_norm = r.tangential_force.norm();
  if (r.normal_force > 0.0) r.force_ratio = r.tangential_force_norm / r.normal_force;
  r.contact_area = r.stick_area + r.slip_area;
  if (r.stick_area > 0.0) {
    r.stick_centroid = weighted / r.stick_area;
    if (state.dim == 2) r.stick_centroid(1) = 0.0;
  }
  r.stick_equivalent_radius = equivalent_radius(r.stick_area, state.dim);
  r.contact_equivalent_radius = equivalent_radius(r.contact_area, state.dim);
  return r;
}

}  // namespace frictopt::contact
