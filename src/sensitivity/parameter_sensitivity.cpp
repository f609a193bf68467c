// SPDX-License-Identifier: MIT
#include "frictopt/sensitivity/parameter_sensitivity.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>

#include "friction_geometry.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::sensitivity {
namespace {

using detail::cross;

}  // namespace

contact::FrictionLaw with_friction_parameters(const contact::FrictionLaw& law, const Eigen::Ref<const Eigen::VectorXd>& values,
                                              FrictionParameterOptions options) {
  const Eigen::Index expected = friction_parameters(law, options).values.size();
  if (values.size() != expected)
    throw InvalidInput(fmt::format("{}: {} friction parameter values given; expected {}", law.describe(), values.size(), expected));
  // The coefficients build the unturned law; the orientation is applied last.
  const double orientation = options.orientation ? values(expected - 1) : law.orientation();
  return law.with_coefficients(values.head(options.orientation ? expected - 1 : expected), orientation);
}

Eigen::MatrixXd friction_parameter_rows(const Piece& piece, const contact::FrictionLaw& law,
                                        const contact::ContactState& state) {
  return friction_parameter_rows(piece, law, state, friction_parameters(law));
}

Eigen::MatrixXd friction_parameter_rows(const Piece& piece, const contact::FrictionLaw& law,
                                        const contact::ContactState& state, const FrictionParameters& params) {
  const Eigen::Index np = params.values.size();
  const int dim = state.dim;
  FRICTOPT_ASSERT(static_cast<Eigen::Index>(piece.nodes.size()) == state.num_nodes(), "piece size");
  Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(dim * state.num_nodes(), np);
  const auto w = law.vertices();
  for (Eigen::Index i = 0; i < state.num_nodes(); ++i) {
    const NodePiece& node = piece.nodes[static_cast<std::size_t>(i)];
    if (node.normal != NormalBranch::kGapClosed) continue;  // λ = 0 and q = 0 rows: no μ
    const Eigen::Index base = dim * i;
    const double lambda = state.lambda(i);
    for (Eigen::Index k = 0; k < np; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      switch (node.tangential) {
        case TangentialBranch::kVertexSlip: {
          const Eigen::Vector2d& dw = params.vertex_derivatives[kk][static_cast<std::size_t>(node.index)];
          for (int c = 0; c < dim - 1; ++c) rows(base + c, k) = -lambda * dw(c);
          break;
        }
        case TangentialBranch::kRaySlip: {
          const std::size_t j = static_cast<std::size_t>(node.index), j1 = (j + 1) % w.size();
          const auto& dv = params.vertex_derivatives[kk];
          const Eigen::Vector2d d = w[j1] - w[j], dd = dv[j1] - dv[j];
          rows(base, k) = cross(dd, state.q(i)) - lambda * (cross(dd, w[j]) + cross(d, dv[j]));
          rows(base + 1, k) = dd.dot(state.u_t(i));
          break;
        }
        case TangentialBranch::kSmoothSlip: {
          Eigen::Vector2d dw = law.exposed_point_coefficient_jacobian(state.u_t(i)) * params.semi_axis_derivatives[kk];
          if (params.orientation_derivatives[kk] != 0.0)
            dw += params.orientation_derivatives[kk] * law.exposed_point_orientation_derivative(state.u_t(i));
          for (int c = 0; c < 2; ++c) rows(base + c, k) = -lambda * dw(c);
          break;
        }
        case TangentialBranch::kStick:
        case TangentialBranch::kZeroFriction: break;
      }
    }
  }
  return rows;
}

ContactStateDerivative contact_state_derivative(const PieceLinearization& piece, const Eigen::MatrixXd& delassus,
                                                const Eigen::Ref<const Eigen::MatrixXd>& contact_rows,
                                                const Eigen::Ref<const Eigen::MatrixXd>& equilibrium_image,
                                                double delassus_scale) {
  const Eigen::Index m = delassus.rows();
  const Eigen::Index k = std::max(contact_rows.cols(), equilibrium_image.cols());
  if (contact_rows.size() && contact_rows.rows() != m)
    throw InvalidInput(fmt::format("contact_state_derivative: contact_rows has {} rows; expected {}", contact_rows.rows(), m));
  if (equilibrium_image.size() && equilibrium_image.rows() != m)
    throw InvalidInput(
        fmt::format("contact_state_derivative: equilibrium_image has {} rows; expected {}", equilibrium_image.rows(), m));
  if (contact_rows.size() && equilibrium_image.size() && contact_rows.cols() != equilibrium_image.cols())
    throw InvalidInput("contact_state_derivative: contact_rows and equilibrium_image have different column counts");
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m, k);
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(m, k);
  if (contact_rows.size()) rhs -= contact_rows;
  if (equilibrium_image.size()) {
    Q = equilibrium_image;
    rhs += piece.S * Q;
  }
  // S has at most two entries per row: a sparse × dense product, not an m³ dense one.
  const Eigen::MatrixXd K = delassus_scale * (piece.S * delassus) + Eigen::MatrixXd(piece.Cz);
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(K);
  ContactStateDerivative out;
  out.reciprocal_condition = lu.rcond();
  out.forces = lu.solve(rhs);
  out.gradient = delassus_scale * (delassus * out.forces) - Q;
  if (!(out.reciprocal_condition > kSingularReciprocalCondition)) {
    out.status = Status::kNumericalFailure;
    out.message = fmt::format("the piece's contact matrix S M + C_z is singular (rcond {:.1e})", out.reciprocal_condition);
  } else {
    out.status = Status::kConverged;
    out.message = "forward sensitivity solved";
  }
  return out;
}

}  // namespace frictopt::sensitivity
