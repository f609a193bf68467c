// SPDX-License-Identifier: MIT
#include "frictopt/sensitivity/friction_parameters.hpp"

#include <cmath>
#include <numbers>

namespace frictopt::sensitivity {
namespace {
// The thesis' directions v_j at φ_j = π(2j+1)/n (0-based; spec 02 §10.2).
Eigen::Vector2d direction(int j, int n) {
  const double phi = std::numbers::pi * (2.0 * j + 1.0) / n;
  return {std::cos(phi), std::sin(phi)};
}
}  // namespace

FrictionParameters friction_parameters(const contact::FrictionLaw& law) {
  using contact::FrictionLawKind;
  FrictionParameters out;
  const auto w = law.vertices();
  const int n = static_cast<int>(w.size());
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
      for (int j = 0; j < n; ++j) d[static_cast<std::size_t>(j)] = direction(j, n);
      out.vertex_derivatives = {d};
      break;
    }
    case FrictionLawKind::kPolygon: {
      out.values.resize(n);
      for (int j = 0; j < n; ++j) {
        out.names.push_back("mu_vertices[" + std::to_string(j) + "]");
        out.values(j) = w[static_cast<std::size_t>(j)].norm();
        auto d = zero_vertices();
        d[static_cast<std::size_t>(j)] = direction(j, n);
        out.vertex_derivatives.push_back(d);
      }
      break;
    }
    case FrictionLawKind::kEllipsePolygon: {
      out.names = {"mu_x", "mu_y"};
      auto dx = zero_vertices(), dy = zero_vertices();
      double mu_x = 0.0, mu_y = 0.0;
      for (int j = 0; j < n; ++j) {
        const Eigen::Vector2d v = direction(j, n);
        dx[static_cast<std::size_t>(j)] = Eigen::Vector2d(v(0), 0.0);
        dy[static_cast<std::size_t>(j)] = Eigen::Vector2d(0.0, v(1));
        if (std::abs(v(0)) > 1e-12) mu_x = w[static_cast<std::size_t>(j)](0) / v(0);
        if (std::abs(v(1)) > 1e-12) mu_y = w[static_cast<std::size_t>(j)](1) / v(1);
      }
      out.values = Eigen::Vector2d(mu_x, mu_y);
      out.vertex_derivatives = {dx, dy};
      break;
    }
    case FrictionLawKind::kDisc:
      out.names = {"mu"};
      out.values = Eigen::VectorXd::Constant(1, law.semi_axes()(0));
      out.semi_axis_derivatives = {Eigen::Vector2d(1.0, 1.0)};
      break;
    case FrictionLawKind::kEllipse:
      out.names = {"mu_x", "mu_y"};
      out.values = law.semi_axes();
      out.semi_axis_derivatives = {Eigen::Vector2d(1.0, 0.0), Eigen::Vector2d(0.0, 1.0)};
      break;
  }
  return out;
}

}  // namespace frictopt::sensitivity
