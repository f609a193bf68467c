// SPDX-License-Identifier: MIT
#include "frictopt/sensitivity/friction_parameters.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "friction_geometry.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::sensitivity {
namespace {
// The thesis' directions v_j at φ_j = π(2j+1)/n (0-based; docs/theory/state-problem.md §3).
Eigen::Vector2d direction(int j, int n) {
  const double phi = std::numbers::pi * (2.0 * j + 1.0) / n;
  return {std::cos(phi), std::sin(phi)};
}

void require_orientable(const contact::FrictionLaw& law) {
  if (law.kind() == contact::FrictionLawKind::kInterval)
    throw InvalidInput(fmt::format("{}: a 2D interval law has no orientation parameter (its tangent space is a line)",
                                   law.describe()));
}

// Appends φ: polygon vertices move by J w_j, smooth sets carry ∂φ/∂p = 1.
void append_orientation(const contact::FrictionLaw& law, FrictionParameters& out) {
  require_orientable(law);
  const Eigen::Index k = out.values.size();
  out.names.push_back("orientation");
  out.values.conservativeResize(k + 1);
  out.values(k) = law.orientation();
  for (double& d : out.orientation_derivatives) d = 0.0;
  if (law.is_polygonal()) {
    std::vector<Eigen::Vector2d> d;
    for (const Eigen::Vector2d& w : law.vertices()) d.push_back(detail::quarter_turn(w));
    out.vertex_derivatives.push_back(std::move(d));
  } else {
    out.semi_axis_derivatives.emplace_back(Eigen::Vector2d::Zero());
    out.orientation_derivatives.push_back(1.0);
  }
}
}  // namespace

FrictionParameters friction_parameters(const contact::FrictionLaw& law, FrictionParameterOptions options) {
  using contact::FrictionLawKind;
  FrictionParameters out;
  const auto w = law.vertices();
  const int n = static_cast<int>(w.size());
  // The coefficients' directions turn with the law: ∂(μ_j R v_j)/∂μ_j = R v_j.
  const Eigen::Matrix2d& R = law.frame();
  const auto zero_vertices = [&] { return std::vector<Eigen::Vector2d>(w.size(), Eigen::Vector2d::Zero()); };
  switch (law.kind()) {
    case FrictionLawKind::kInterval: {
      out.names = {"mu_minus", "mu_plus"};
      out.values = Eigen::Vector2d(-w[0](0), w[1](0));
      auto d_minus = zero_vertices(), d_plus = zero_vertices();
      d_minus[0] = Eigen::Vector2d(-1.0, 0.0);
      d_plus[1] = Eigen::Vector2d(1.0, 0.0);
      out.vertex_derivatives = {d_minus, d_plus};
      break;
    }
    case FrictionLawKind::kRegularPolygon: {
      out.names = {"mu"};
      out.values = Eigen::VectorXd::Constant(1, law.max_coefficient());
      auto d = zero_vertices();
      for (int j = 0; j < n; ++j) d[static_cast<std::size_t>(j)] = R * direction(j, n);
      out.vertex_derivatives = {d};
      break;
    }
    case FrictionLawKind::kPolygon: {
      out.values.resize(n);
      for (int j = 0; j < n; ++j) {
        out.names.push_back("mu_vertices[" + std::to_string(j) + "]");
        out.values(j) = w[static_cast<std::size_t>(j)].norm();
        auto d = zero_vertices();
        d[static_cast<std::size_t>(j)] = R * direction(j, n);
        out.vertex_derivatives.push_back(d);
      }
      break;
    }
    case FrictionLawKind::kEllipsePolygon: {
      out.names = {"mu_x", "mu_y"};
      auto dx = zero_vertices(), dy = zero_vertices();
      for (int j = 0; j < n; ++j) {
        const Eigen::Vector2d v = direction(j, n);
        dx[static_cast<std::size_t>(j)] = R * Eigen::Vector2d(v(0), 0.0);
        dy[static_cast<std::size_t>(j)] = R * Eigen::Vector2d(0.0, v(1));
      }
      out.values = law.semi_axes();
      out.vertex_derivatives = {dx, dy};
      break;
    }
    case FrictionLawKind::kDisc:
      out.names = {"mu"};
      out.values = Eigen::VectorXd::Constant(1, law.semi_axes()(0));
      out.semi_axis_derivatives = {Eigen::Vector2d(1.0, 1.0)};
      out.orientation_derivatives = {0.0};
      break;
    case FrictionLawKind::kEllipse:
      out.names = {"mu_x", "mu_y"};
      out.values = law.semi_axes();
      out.semi_axis_derivatives = {Eigen::Vector2d(1.0, 0.0), Eigen::Vector2d(0.0, 1.0)};
      out.orientation_derivatives = {0.0, 0.0};
      break;
  }
  if (options.orientation) append_orientation(law, out);
  return out;
}

FrictionParameters orientation_parameter(const contact::FrictionLaw& law) {
  FrictionParameters out;
  append_orientation(law, out);
  return out;
}

}  // namespace frictopt::sensitivity
