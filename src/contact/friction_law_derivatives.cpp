// SPDX-License-Identifier: MIT
// The local geometry of a friction set W and its derivatives, per law kind: gauge and radial
// function, the projection's and the exposed point's Jacobians, the exposed point's derivative
// by the orientation and by the law's own coefficients (docs/contact.md, "Friction laws" and
// "Adding a friction law"; docs/theory/friction-frame.md for the turned laws).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "frictopt/contact/friction_law.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::contact {
namespace {

/// J v: v turned by +90° (J = R(π/2); the derivative of R(φ) is J R(φ)).
Eigen::Vector2d quarter_turn(const Eigen::Vector2d& v) { return {-v(1), v(0)}; }

/// The thesis' directions v_j at φ_j = π(2j+1)/n (0-based; FrictionLaw::regular_polygon).
Eigen::Vector2d direction(int j, int n) {
  const double phi = std::numbers::pi * (2.0 * j + 1.0) / n;
  return {std::cos(phi), std::sin(phi)};
}

/// ∂w₀/∂d of the exposed point w₀(d) = A d/√(dᵀAd), A = diag(a², b²), of the unturned
/// disc/ellipse with semi-axes (a, b): A/σ − (Ad)(Ad)ᵀ/σ³, σ = √(dᵀAd).
Eigen::Matrix2d ellipse_exposed_point_jacobian(const Eigen::Vector2d& semi_axes, const Eigen::Vector2d& d) {
  const Eigen::Matrix2d A = semi_axes.cwiseProduct(semi_axes).asDiagonal();
  const Eigen::Vector2d Ad = A * d;
  const double s = std::sqrt(d.dot(Ad));
  return A / s - Ad * Ad.transpose() / (s * s * s);
}

/// ∂w₀/∂(a, b) of the same exposed point (columns ∂/∂a, ∂/∂b).
Eigen::Matrix2d ellipse_exposed_point_axis_jacobian(const Eigen::Vector2d& semi_axes, const Eigen::Vector2d& d) {
  const double a = semi_axes(0), b = semi_axes(1);
  const double s = std::sqrt(a * a * d(0) * d(0) + b * b * d(1) * d(1));
  const double ds_da = a * d(0) * d(0) / s, ds_db = b * d(1) * d(1) / s;
  Eigen::Matrix2d J;
  J(0, 0) = 2 * a * d(0) / s - a * a * d(0) * ds_da / (s * s);
  J(1, 0) = -b * b * d(1) * ds_da / (s * s);
  J(0, 1) = -a * a * d(0) * ds_db / (s * s);
  J(1, 1) = 2 * b * d(1) / s - b * b * d(1) * ds_db / (s * s);
  return J;
}

}  // namespace

bool FrictionLaw::is_isotropic() const {
  if (zero_) return true;
  switch (kind_) {
    case FrictionLawKind::kInterval: return mu_vertices_[0] == mu_vertices_[1];
    case FrictionLawKind::kDisc: return true;
    case FrictionLawKind::kEllipse: return semi_axes_(0) == semi_axes_(1);
    case FrictionLawKind::kRegularPolygon:
    case FrictionLawKind::kPolygon:
    case FrictionLawKind::kEllipsePolygon: return false;
  }
  unknown_kind(kind_, "is_isotropic");
}

double FrictionLaw::gauge(const Eigen::Vector2d& x) const {
  if (zero_) return x.isZero(0.0) ? 0.0 : std::numeric_limits<double>::infinity();
  switch (kind_) {
    case FrictionLawKind::kInterval:
      if (x(0) == 0.0) return 0.0;
      return x(0) > 0 ? x(0) / vertices_[1](0) : x(0) / vertices_[0](0);
    case FrictionLawKind::kDisc:
    case FrictionLawKind::kEllipse: {
      const Eigen::Vector2d xl = frame_.transpose() * x;  // in the law's own axes
      return std::hypot(xl(0) / semi_axes_(0), xl(1) / semi_axes_(1));
    }
    case FrictionLawKind::kRegularPolygon:
    case FrictionLawKind::kPolygon:
    case FrictionLawKind::kEllipsePolygon: {
      // W = {⟨e_j, w⟩ <= h_j ∀j}, so x ∈ tW ⇔ t >= max_j ⟨e_j, x⟩/h_j (and t >= 0).
      double g = 0.0;
      for (std::size_t j = 0; j < normals_.size(); ++j) g = std::max(g, normals_[j].dot(x) / heights_[j]);
      return g;
    }
  }
  unknown_kind(kind_, "gauge");
}

double FrictionLaw::radial(const Eigen::Vector2d& d) const {
  FRICTOPT_ASSERT(!d.isZero(0.0), "FrictionLaw::radial: zero direction");
  return 1.0 / gauge(d);
}

FrictionLaw::ProjectionJacobian FrictionLaw::projection_jacobian(const Eigen::Vector2d& y_in) const {
  ProjectionJacobian out;
  if (zero_) return out;
  Eigen::Vector2d y = y_in;
  if (dim() == 2) y.y() = 0.0;
  out.point = project(y, 1.0);
  Eigen::Matrix2d& J = out.jacobian;
  if (boundary_offset(y, 1.0) <= 0.0) {
    J.setIdentity();
    out.face = {FrictionFace::kInterior, -1};
  } else {
    bool listed = false;  // a kind this switch does not list must not keep J = 0 silently
    switch (kind_) {
      case FrictionLawKind::kInterval:
      case FrictionLawKind::kRegularPolygon:
      case FrictionLawKind::kPolygon:
      case FrictionLawKind::kEllipsePolygon: {
        // The face of the projection, with a tolerance relative to the set's size: the
        // projection is exact to rounding, so 1e-12·max|w| separates an edge point from a
        // vertex robustly. A vertex: P is locally constant; an edge: P moves along it.
        out.face = locate(out.point, 1.0, 1e-12 * max_coefficient_);
        if (out.face.face == FrictionFace::kEdge) {
          const Eigen::Vector2d e = normals_[static_cast<std::size_t>(out.face.index)];
          const Eigen::Vector2d t(-e.y(), e.x());
          J = t * t.transpose();
        } else {
          J.setZero();
        }
        listed = true;
        break;
      }
      case FrictionLawKind::kDisc:
      case FrictionLawKind::kEllipse: {
        // In the law's own frame: R J₀(Rᵀy, Rᵀp) Rᵀ.
        const Eigen::Matrix2d& R = frame_;
        const Eigen::Vector2d yl = R.transpose() * y, p = R.transpose() * out.point;
        const Eigen::Vector2d D(1.0 / (semi_axes_.x() * semi_axes_.x()), 1.0 / (semi_axes_.y() * semi_axes_.y()));
        const Eigen::Vector2d Dp = D.cwiseProduct(p);
        // y − p = γ D p: the multiplier in the least-squares sense (exact up to the
        // projection's rounding).
        const double gamma = std::max(0.0, (yl - p).dot(Dp) / Dp.squaredNorm());
        const Eigen::Vector2d M = (Eigen::Vector2d::Ones() + gamma * D).cwiseInverse();
        const Eigen::Vector2d MDp = M.cwiseProduct(Dp);
        J = R * (Eigen::Matrix2d(M.asDiagonal()) - MDp * MDp.transpose() / Dp.dot(MDp)) * R.transpose();
        out.face = {FrictionFace::kSmooth, -1};
        listed = true;
        break;
      }
    }
    if (!listed) unknown_kind(kind_, "projection_jacobian");
  }
  if (dim() == 2) J(0, 1) = J(1, 0) = J(1, 1) = 0.0;  // one tangential component
  return out;
}

Eigen::Matrix2d FrictionLaw::exposed_point_jacobian(const Eigen::Vector2d& u) const {
  if (zero_ || u.isZero(0.0)) return Eigen::Matrix2d::Zero();
  switch (kind_) {
    case FrictionLawKind::kInterval:
    case FrictionLawKind::kRegularPolygon:
    case FrictionLawKind::kPolygon:
    case FrictionLawKind::kEllipsePolygon: return Eigen::Matrix2d::Zero();
    case FrictionLawKind::kDisc:
    case FrictionLawKind::kEllipse: {
      // w(u) = R w₀(Rᵀu), so ∂w/∂u = R (∂w₀/∂d)(Rᵀu) Rᵀ.
      const Eigen::Matrix2d& R = frame_;
      return R * ellipse_exposed_point_jacobian(semi_axes_, R.transpose() * u) * R.transpose();
    }
  }
  unknown_kind(kind_, "exposed_point_jacobian");
}

Eigen::Vector2d FrictionLaw::exposed_point_orientation_derivative(const Eigen::Vector2d& u) const {
  return quarter_turn(exposed_point(u)) - exposed_point_jacobian(u) * quarter_turn(u);
}

// ---------------------------------------------------------------------------------------------
// Coefficients

std::vector<std::string> FrictionLaw::coefficient_names() const {
  switch (kind_) {
    case FrictionLawKind::kInterval: return {"mu_minus", "mu_plus"};
    case FrictionLawKind::kDisc:
    case FrictionLawKind::kRegularPolygon: return {"mu"};
    case FrictionLawKind::kPolygon: {
      std::vector<std::string> names;
      for (std::size_t j = 0; j < vertices_.size(); ++j) names.push_back("mu_vertices[" + std::to_string(j) + "]");
      return names;
    }
    case FrictionLawKind::kEllipse:
    case FrictionLawKind::kEllipsePolygon: return {"mu_x", "mu_y"};
  }
  unknown_kind(kind_, "coefficient_names");
}

Eigen::VectorXd FrictionLaw::coefficients() const {
  switch (kind_) {
    case FrictionLawKind::kInterval: return Eigen::Vector2d(-vertices_[0](0), vertices_[1](0));
    case FrictionLawKind::kDisc: return Eigen::VectorXd::Constant(1, semi_axes_(0));
    case FrictionLawKind::kRegularPolygon: return Eigen::VectorXd::Constant(1, max_coefficient_);
    case FrictionLawKind::kPolygon: {
      // |w_j| of the stored (possibly turned) vertices: μ_j up to the rounding of the turn.
      Eigen::VectorXd c(static_cast<Eigen::Index>(vertices_.size()));
      for (std::size_t j = 0; j < vertices_.size(); ++j) c(static_cast<Eigen::Index>(j)) = vertices_[j].norm();
      return c;
    }
    case FrictionLawKind::kEllipse:
    case FrictionLawKind::kEllipsePolygon: return semi_axes_;
  }
  unknown_kind(kind_, "coefficients");
}

FrictionLaw FrictionLaw::with_coefficients(const Eigen::Ref<const Eigen::VectorXd>& mu, double orientation) const {
  const Eigen::Index expected = static_cast<Eigen::Index>(coefficient_names().size());
  if (mu.size() != expected)
    throw InvalidInput(describe() + ": " + std::to_string(mu.size()) + " coefficient values given; expected " +
                       std::to_string(expected));
  const int n = static_cast<int>(vertices_.size());
  const auto unturned = [&]() -> FrictionLaw {
    switch (kind_) {
      case FrictionLawKind::kInterval: return interval(mu(0), mu(1));
      case FrictionLawKind::kDisc: return disc(mu(0));
      case FrictionLawKind::kRegularPolygon: return regular_polygon(mu(0), n);
      case FrictionLawKind::kPolygon: return polygon({mu.data(), mu.data() + mu.size()});
      case FrictionLawKind::kEllipse: return ellipse(mu(0), mu(1));
      case FrictionLawKind::kEllipsePolygon: return ellipse_polygon(mu(0), mu(1), n);
    }
    unknown_kind(kind_, "with_coefficients");
  };
  return unturned().rotated(orientation);
}

std::vector<std::vector<Eigen::Vector2d>> FrictionLaw::vertex_coefficient_derivatives() const {
  const std::size_t nv = vertices_.size();
  const int n = static_cast<int>(nv);
  // The coefficients' directions turn with the law: ∂(μ_j R v_j)/∂μ_j = R v_j.
  const Eigen::Matrix2d& R = frame_;
  const auto zero_vertices = [&] { return std::vector<Eigen::Vector2d>(nv, Eigen::Vector2d::Zero()); };
  std::vector<std::vector<Eigen::Vector2d>> out;
  switch (kind_) {
    case FrictionLawKind::kDisc:
    case FrictionLawKind::kEllipse: return out;
    case FrictionLawKind::kInterval: {
      auto d_minus = zero_vertices(), d_plus = zero_vertices();
      d_minus[0] = Eigen::Vector2d(-1.0, 0.0);
      d_plus[1] = Eigen::Vector2d(1.0, 0.0);
      out = {d_minus, d_plus};
      return out;
    }
    case FrictionLawKind::kRegularPolygon: {
      auto d = zero_vertices();
      for (int j = 0; j < n; ++j) d[static_cast<std::size_t>(j)] = R * direction(j, n);
      out = {d};
      return out;
    }
    case FrictionLawKind::kPolygon:
      for (int j = 0; j < n; ++j) {
        auto d = zero_vertices();
        d[static_cast<std::size_t>(j)] = R * direction(j, n);
        out.push_back(d);
      }
      return out;
    case FrictionLawKind::kEllipsePolygon: {
      auto dx = zero_vertices(), dy = zero_vertices();
      for (int j = 0; j < n; ++j) {
        const Eigen::Vector2d v = direction(j, n);
        dx[static_cast<std::size_t>(j)] = R * Eigen::Vector2d(v(0), 0.0);
        dy[static_cast<std::size_t>(j)] = R * Eigen::Vector2d(0.0, v(1));
      }
      out = {dx, dy};
      return out;
    }
  }
  unknown_kind(kind_, "vertex_coefficient_derivatives");
}

Eigen::MatrixXd FrictionLaw::exposed_point_coefficient_jacobian(const Eigen::Vector2d& u) const {
  const auto nc = static_cast<Eigen::Index>(coefficient_names().size());
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2, nc);
  if (zero_ || u.isZero(0.0)) return J;
  switch (kind_) {
    case FrictionLawKind::kDisc:
    case FrictionLawKind::kEllipse: {
      // ∂/∂(μ_x, μ_y) of R w₀(Rᵀu); the disc's μ moves both semi-axes.
      const Eigen::Matrix2d axes = frame_ * ellipse_exposed_point_axis_jacobian(semi_axes_, frame_.transpose() * u);
      if (kind_ == FrictionLawKind::kDisc) {
        const Eigen::Vector2d both = axes * Eigen::Vector2d(1.0, 1.0);
        J(0, 0) = both(0);
        J(1, 0) = both(1);
      } else {
        J = axes;
      }
      return J;
    }
    case FrictionLawKind::kInterval:
    case FrictionLawKind::kRegularPolygon:
    case FrictionLawKind::kPolygon:
    case FrictionLawKind::kEllipsePolygon: {
      // w(u) = w_j for the exposed vertex j (exposed_point's choice), so ∂w/∂c_k = ∂w_j/∂c_k.
      // (A 2D u = (0, ·) exposes no vertex: w = 0.)
      const Eigen::Vector2d w = exposed_point(u);
      std::size_t j = 0;
      while (j < vertices_.size() && vertices_[j] != w) ++j;
      if (j == vertices_.size()) return J;
      const auto d = vertex_coefficient_derivatives();
      for (Eigen::Index k = 0; k < nc; ++k) J.col(k) = d[static_cast<std::size_t>(k)][j];
      return J;
    }
  }
  unknown_kind(kind_, "exposed_point_coefficient_jacobian");
}

}  // namespace frictopt::contact
