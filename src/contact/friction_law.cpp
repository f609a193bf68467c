// SPDX-License-Identifier: MIT
#include "frictopt/contact/friction_law.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "frictopt/core/enum_table.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::contact {
namespace {

constexpr frictopt::detail::EnumTable<FrictionLawKind, 6> kKindNames{{{
    {FrictionLawKind::kInterval, "interval"},
    {FrictionLawKind::kDisc, "disc"},
    {FrictionLawKind::kRegularPolygon, "regular_polygon"},
    {FrictionLawKind::kPolygon, "polygon"},
    {FrictionLawKind::kEllipse, "ellipse"},
    {FrictionLawKind::kEllipsePolygon, "ellipse_polygon"},
}}};

constexpr frictopt::detail::EnumTable<FrictionFace, 5> kFaceNames{{{
    {FrictionFace::kInterior, "interior"},
    {FrictionFace::kEdge, "edge"},
    {FrictionFace::kVertex, "vertex"},
    {FrictionFace::kSmooth, "smooth"},
    {FrictionFace::kDegenerate, "degenerate"},
}}};


std::string num(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

void require_coefficient(double mu, const char* context, const std::string& field) {
  if (!std::isfinite(mu) || mu < 0.0)
    throw InvalidInput(std::string(context) + ": " + field + " = " + num(mu) +
                       "; expected a finite value >= 0");
}

void require_vertex_count(int n, const char* context) {
  if (n < 3)
    throw InvalidInput(std::string(context) + ": n = " + std::to_string(n) +
                       "; expected n >= 3 vertices");
}

/// Thesis vertex directions v_j, φ_j = π(2j−1)/n for j = 1..n (0-based: π(2j+1)/n).
double vertex_angle(int j, int n) { return std::numbers::pi * (2.0 * j + 1.0) / n; }

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Projection of q onto the segment [a, b].
Eigen::Vector2d project_segment(const Eigen::Vector2d& q, const Eigen::Vector2d& a,
                                const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const double dd = d.squaredNorm();
  if (dd == 0.0) return a;
  const double t = std::clamp((q - a).dot(d) / dd, 0.0, 1.0);
  return a + t * d;
}

/// Largest α >= 0 with ‖q + α d‖ <= 1 for ‖q‖ <= 1 (the positive root of a quadratic).
double disc_max_step(const Eigen::Vector2d& q, const Eigen::Vector2d& d) {
  const double dd = d.squaredNorm();
  if (dd == 0.0) return std::numeric_limits<double>::infinity();
  const double qd = q.dot(d);
  const double slack = std::max(0.0, 1.0 - q.squaredNorm());
  const double disc = std::sqrt(qd * qd + dd * slack);
  // Stable form of (−qd + disc)/dd: avoid cancellation when qd > 0.
  return qd > 0.0 ? slack / (qd + disc) : (disc - qd) / dd;
}

}  // namespace

std::string_view to_string(FrictionLawKind kind) { return kKindNames.name(kind); }
FrictionLawKind parse_friction_law_kind(std::string_view text) { return kKindNames.parse(text, "friction law kind"); }
std::string_view to_string(FrictionFace face) { return kFaceNames.name(face); }
FrictionFace parse_friction_face(std::string_view text) { return kFaceNames.parse(text, "friction face"); }

// ---------------------------------------------------------------------------------------------
// Factories

FrictionLaw FrictionLaw::interval(double mu_minus, double mu_plus) {
  require_coefficient(mu_minus, "FrictionLaw::interval", "mu_minus");
  require_coefficient(mu_plus, "FrictionLaw::interval", "mu_plus");
  FrictionLaw law;
  law.kind_ = FrictionLawKind::kInterval;
  law.zero_ = mu_minus == 0.0 && mu_plus == 0.0;
  law.max_coefficient_ = std::max(mu_minus, mu_plus);
  law.min_coefficient_ = std::min(mu_minus, mu_plus);
  law.mu_vertices_ = {mu_minus, mu_plus};
  law.vertices_ = {Eigen::Vector2d(-mu_minus, 0.0), Eigen::Vector2d(mu_plus, 0.0)};
  return law;
}

FrictionLaw FrictionLaw::disc(double mu) {
  require_coefficient(mu, "FrictionLaw::disc", "mu");
  FrictionLaw law;
  law.kind_ = FrictionLawKind::kDisc;
  law.zero_ = mu == 0.0;
  law.max_coefficient_ = law.min_coefficient_ = mu;
  law.semi_axes_ = Eigen::Vector2d(mu, mu);
  return law;
}

FrictionLaw FrictionLaw::ellipse(double mu_x, double mu_y) {
  require_coefficient(mu_x, "FrictionLaw::ellipse", "mu_x");
  require_coefficient(mu_y, "FrictionLaw::ellipse", "mu_y");
  if ((mu_x == 0.0) != (mu_y == 0.0))
    throw InvalidInput("FrictionLaw::ellipse: mu_x = " + num(mu_x) + ", mu_y = " + num(mu_y) +
                       "; expected both > 0 (or both = 0 for no friction)");
  FrictionLaw law;
  law.kind_ = FrictionLawKind::kEllipse;
  law.zero_ = mu_x == 0.0;
  law.max_coefficient_ = std::max(mu_x, mu_y);
  law.min_coefficient_ = std::min(mu_x, mu_y);
  law.semi_axes_ = Eigen::Vector2d(mu_x, mu_y);
  return law;
}

FrictionLaw FrictionLaw::regular_polygon(double mu, int n) {
  require_coefficient(mu, "FrictionLaw::regular_polygon", "mu");
  require_vertex_count(n, "FrictionLaw::regular_polygon");
  std::vector<Eigen::Vector2d> w(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j)
    w[static_cast<std::size_t>(j)] =
        mu * Eigen::Vector2d(std::cos(vertex_angle(j, n)), std::sin(vertex_angle(j, n)));
  return make_polygon(FrictionLawKind::kRegularPolygon, std::move(w),
                      std::vector<double>(static_cast<std::size_t>(n), mu),
                      "FrictionLaw::regular_polygon");
}

FrictionLaw FrictionLaw::polygon(std::vector<double> mu_vertices) {
  const int n = static_cast<int>(mu_vertices.size());
  require_vertex_count(n, "FrictionLaw::polygon");
  for (int j = 0; j < n; ++j)
    require_coefficient(mu_vertices[static_cast<std::size_t>(j)], "FrictionLaw::polygon",
                        "mu[" + std::to_string(j) + "]");
  const bool all_zero =
      std::all_of(mu_vertices.begin(), mu_vertices.end(), [](double m) { return m == 0.0; });
  if (!all_zero)
    for (int j = 0; j < n; ++j)
      if (mu_vertices[static_cast<std::size_t>(j)] == 0.0)
        throw InvalidInput("FrictionLaw::polygon: mu[" + std::to_string(j) +
                           "] = 0 while other coefficients are > 0; expected every mu_j > 0 "
                           "(or all = 0 for no friction), since a zero vertex puts the origin "
                           "on the boundary");
  std::vector<Eigen::Vector2d> w(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j)
    w[static_cast<std::size_t>(j)] =
        mu_vertices[static_cast<std::size_t>(j)] *
        Eigen::Vector2d(std::cos(vertex_angle(j, n)), std::sin(vertex_angle(j, n)));
  return make_polygon(FrictionLawKind::kPolygon, std::move(w), std::move(mu_vertices),
                      "FrictionLaw::polygon");
}

FrictionLaw FrictionLaw::ellipse_polygon(double mu_x, double mu_y, int n) {
  require_coefficient(mu_x, "FrictionLaw::ellipse_polygon", "mu_x");
  require_coefficient(mu_y, "FrictionLaw::ellipse_polygon", "mu_y");
  require_vertex_count(n, "FrictionLaw::ellipse_polygon");
  if ((mu_x == 0.0) != (mu_y == 0.0))
    throw InvalidInput("FrictionLaw::ellipse_polygon: mu_x = " + num(mu_x) + ", mu_y = " +
                       num(mu_y) + "; expected both > 0 (or both = 0 for no friction)");
  std::vector<Eigen::Vector2d> w(static_cast<std::size_t>(n));
  std::vector<double> mu(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    w[static_cast<std::size_t>(j)] = Eigen::Vector2d(mu_x * std::cos(vertex_angle(j, n)),
                                                     mu_y * std::sin(vertex_angle(j, n)));
    mu[static_cast<std::size_t>(j)] = w[static_cast<std::size_t>(j)].norm();
  }
  FrictionLaw law =
      make_polygon(FrictionLawKind::kEllipsePolygon, std::move(w), std::move(mu),
                   "FrictionLaw::ellipse_polygon");
  law.semi_axes_ = Eigen::Vector2d(mu_x, mu_y);
  return law;
}

FrictionLaw FrictionLaw::make_polygon(FrictionLawKind kind, std::vector<Eigen::Vector2d> w,
                                      std::vector<double> mu_vertices, const char* context) {
  FrictionLaw law;
  law.kind_ = kind;
  law.mu_vertices_ = std::move(mu_vertices);
  const int n = static_cast<int>(w.size());
  law.zero_ = std::all_of(w.begin(), w.end(), [](const Eigen::Vector2d& v) { return v.isZero(0.0); });
  if (law.zero_) {
    law.vertices_ = std::move(w);
    return law;
  }
  // Every vertex must be a strict corner of a counter-clockwise convex polygon. The relative
  // threshold 1e-12 on sin(turning angle) rejects collinear vertices up to rounding of the
  // vertex coordinates (~1e-16 relative) with a wide margin.
  constexpr double kMinTurnSine = 1e-12;
  auto at = [&](int j) -> const Eigen::Vector2d& { return w[static_cast<std::size_t>((j + n) % n)]; };
  auto mu_at = [&](int j) { return law.mu_vertices_[static_cast<std::size_t>((j + n) % n)]; };
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector2d a = at(j) - at(j - 1);
    const Eigen::Vector2d b = at(j + 1) - at(j);
    const double turn = cross(a, b);
    if (!(turn > kMinTurnSine * a.norm() * b.norm()))
      throw InvalidInput(std::string(context) + ": vertex " + std::to_string(j) + " (mu[" +
                         std::to_string(j) + "] = " + num(mu_at(j)) + ", neighbours mu[" +
                         std::to_string((j - 1 + n) % n) + "] = " + num(mu_at(j - 1)) + ", mu[" +
                         std::to_string((j + 1) % n) + "] = " + num(mu_at(j + 1)) + ") is " +
                         (turn < 0.0 ? "reflex" : "collinear with its neighbours") +
                         " (turn = " + num(turn) +
                         "); expected a convex polygon in which every vertex is a corner");
  }
  law.normals_.resize(static_cast<std::size_t>(n));
  law.heights_.resize(static_cast<std::size_t>(n));
  law.max_coefficient_ = 0.0;
  law.min_coefficient_ = std::numeric_limits<double>::infinity();
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector2d d = at(j + 1) - at(j);
    const Eigen::Vector2d e = Eigen::Vector2d(d.y(), -d.x()).normalized();
    const double h = e.dot(at(j));
    if (!(h > 0.0))
      throw InvalidInput(std::string(context) + ": edge " + std::to_string(j) +
                         " has height " + num(h) + "; expected the origin strictly inside");
    law.normals_[static_cast<std::size_t>(j)] = e;
    law.heights_[static_cast<std::size_t>(j)] = h;
    law.max_coefficient_ = std::max(law.max_coefficient_, at(j).norm());
    law.min_coefficient_ = std::min(law.min_coefficient_, h);
  }
  law.vertices_ = std::move(w);
  return law;
}

FrictionLaw FrictionLaw::rotated(double angle) const {
  if (!std::isfinite(angle))
    throw InvalidInput("FrictionLaw::rotated: angle = " + num(angle) + "; expected a finite angle in radians");
  if (angle == 0.0) return *this;
  if (kind_ == FrictionLawKind::kInterval)
    throw InvalidInput("FrictionLaw::rotated: " + describe() + " is a 2D law (its tangent space is a line); angle = " +
                       num(angle) + "; expected 0");
  FrictionLaw law = *this;
  law.orientation_ = orientation_ + angle;
  // R(φ) from the total angle (not a product of turns), so frame() does not drift with the
  // number of rotated() calls.
  const double c = std::cos(law.orientation_), s = std::sin(law.orientation_);
  law.frame_ << c, -s, s, c;
  // Polygons turn by the increment: vertices and normals are stored in the tangent plane.
  const double ci = std::cos(angle), si = std::sin(angle);
  Eigen::Matrix2d turn;
  turn << ci, -si, si, ci;
  for (auto& w : law.vertices_) w = turn * w;
  for (auto& e : law.normals_) e = turn * e;
  return law;
}

// ---------------------------------------------------------------------------------------------
// Geometry

bool FrictionLaw::is_polygonal() const {
  switch (kind_) {
    case FrictionLawKind::kInterval:
    case FrictionLawKind::kRegularPolygon:
    case FrictionLawKind::kPolygon:
    case FrictionLawKind::kEllipsePolygon: return true;
    case FrictionLawKind::kDisc:
    case FrictionLawKind::kEllipse: return false;
  }
  unknown_kind(kind_, "is_polygonal");
}

void FrictionLaw::unknown_kind(FrictionLawKind kind, const char* where) {
  throw std::logic_error("FrictionLaw::" + std::string(where) + ": unknown friction law kind " +
                         std::to_string(static_cast<int>(kind)));
}

Eigen::Vector2d FrictionLaw::project(const Eigen::Vector2d& q, double s) const {
  FRICTOPT_ASSERT(s >= 0.0, "FrictionLaw::project: negative slip bound");
  if (zero_ || s <= 0.0) return Eigen::Vector2d::Zero();
  switch (kind_) {
    case FrictionLawKind::kInterval:
      return Eigen::Vector2d(std::clamp(q.x(), -s * mu_vertices_[0], s * mu_vertices_[1]), 0.0);
    case FrictionLawKind::kDisc: {
      const double r = s * semi_axes_.x();
      const double nq = q.norm();
      return nq <= r ? q : Eigen::Vector2d(q * (r / nq));
    }
    case FrictionLawKind::kEllipse: {
      // min ‖x − q‖² s.t. (x/a)² + (y/b)² <= 1: x_k = a_k² q_k/(a_k² + t) with t >= 0 the root
      // of f(t) = Σ (a_k q_k/(a_k² + t))² − 1, which is convex and decreasing; Newton from a
      // lower bound of the root increases monotonically to it (no safeguard needed).
      // In the law's own frame (a rotation preserves distances, so the projection commutes
      // with it).
      const Eigen::Vector2d a = s * semi_axes_;
      const Eigen::Vector2d ql = to_law_frame(q);
      const Eigen::Vector2d aq = a.cwiseProduct(ql);
      if ((ql.cwiseQuotient(a)).squaredNorm() <= 1.0) return q;
      double t = std::max({0.0, std::abs(aq.x()) - a.x() * a.x(), std::abs(aq.y()) - a.y() * a.y()});
      for (int it = 0; it < 100; ++it) {
        const Eigen::Vector2d den = (a.cwiseProduct(a)).array() + t;
        const Eigen::Vector2d r = aq.cwiseQuotient(den);
        const double f = r.squaredNorm() - 1.0;
        const double df = -2.0 * (r.cwiseProduct(r).cwiseQuotient(den)).sum();
        if (f <= 0.0 || df == 0.0) break;
        const double step = -f / df;
        t += step;
        if (step <= 4.0 * std::numeric_limits<double>::epsilon() * t) break;
      }
      const Eigen::Vector2d den = (a.cwiseProduct(a)).array() + t;
      return from_law_frame(a.cwiseProduct(aq).cwiseQuotient(den));
    }
    case FrictionLawKind::kRegularPolygon:
    case FrictionLawKind::kPolygon:
    case FrictionLawKind::kEllipsePolygon: {
      const int n = static_cast<int>(vertices_.size());
      bool inside = true;
      for (int j = 0; j < n && inside; ++j)
        inside = normals_[static_cast<std::size_t>(j)].dot(q) <= s * heights_[static_cast<std::size_t>(j)];
      if (inside) return q;
      Eigen::Vector2d best = Eigen::Vector2d::Zero();
      double best_d2 = std::numeric_limits<double>::infinity();
      for (int j = 0; j < n; ++j) {
        const Eigen::Vector2d p = project_segment(q, s * vertices_[static_cast<std::size_t>(j)],
                                                  s * vertices_[static_cast<std::size_t>((j + 1) % n)]);
        const double d2 = (p - q).squaredNorm();
        if (d2 < best_d2) {
          best_d2 = d2;
          best = p;
        }
      }
      return best;
    }
  }
  unknown_kind(kind_, "project");
}

double FrictionLaw::project(double q, double s) const {
  return project(Eigen::Vector2d(q, 0.0), s).x();
}

double FrictionLaw::support(const Eigen::Vector2d& u) const {
  if (zero_) return 0.0;
  switch (kind_) {
    case FrictionLawKind::kInterval:
      return u.x() >= 0.0 ? mu_vertices_[1] * u.x() : -mu_vertices_[0] * u.x();
    case FrictionLawKind::kDisc:  // rotation-invariant: no turn, no rounding
      return semi_axes_.cwiseProduct(u).norm();
    case FrictionLawKind::kEllipse:
      return semi_axes_.cwiseProduct(to_law_frame(u)).norm();
    case FrictionLawKind::kRegularPolygon:
    case FrictionLawKind::kPolygon:
    case FrictionLawKind::kEllipsePolygon: {
      double best = -std::numeric_limits<double>::infinity();
      for (const auto& w : vertices_) best = std::max(best, w.dot(u));
      return best;
    }
  }
  unknown_kind(kind_, "support");
}

double FrictionLaw::support(double u) const { return support(Eigen::Vector2d(u, 0.0)); }

Eigen::Vector2d FrictionLaw::exposed_point(const Eigen::Vector2d& u) const {
  if (zero_) return Eigen::Vector2d::Zero();
  switch (kind_) {
    case FrictionLawKind::kInterval:
      if (u.x() > 0.0) return vertices_[1];
      if (u.x() < 0.0) return vertices_[0];
      return Eigen::Vector2d::Zero();
    case FrictionLawKind::kDisc:
    case FrictionLawKind::kEllipse: {
      // ∇N_W(u) = R diag(μ²) Rᵀu / ‖diag(μ) Rᵀu‖ (the disc's R is harmless: diag(μ²) = μ² I).
      const Eigen::Vector2d ul = kind_ == FrictionLawKind::kDisc ? u : to_law_frame(u);
      const double nu = semi_axes_.cwiseProduct(ul).norm();
      if (nu == 0.0) return Eigen::Vector2d::Zero();
      const Eigen::Vector2d w = semi_axes_.cwiseProduct(semi_axes_).cwiseProduct(ul) / nu;
      return kind_ == FrictionLawKind::kDisc ? w : from_law_frame(w);
    }
    case FrictionLawKind::kRegularPolygon:
    case FrictionLawKind::kPolygon:
    case FrictionLawKind::kEllipsePolygon: {
      if (u.isZero(0.0)) return Eigen::Vector2d::Zero();
      std::size_t best = 0;
      for (std::size_t j = 1; j < vertices_.size(); ++j)
        if (vertices_[j].dot(u) > vertices_[best].dot(u)) best = j;
      return vertices_[best];
    }
  }
  unknown_kind(kind_, "exposed_point");
}

double FrictionLaw::max_step(const Eigen::Vector2d& q, double s, const Eigen::Vector2d& d) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (d.isZero(0.0)) return kInf;
  if (zero_ || s <= 0.0) return 0.0;
  switch (kind_) {
    case FrictionLawKind::kInterval: {
      if (d.x() > 0.0) return std::max(0.0, (s * mu_vertices_[1] - q.x()) / d.x());
      if (d.x() < 0.0) return std::max(0.0, (-s * mu_vertices_[0] - q.x()) / d.x());
      return kInf;
    }
    case FrictionLawKind::kDisc:
    case FrictionLawKind::kEllipse: {
      const Eigen::Vector2d a = s * semi_axes_;
      if (kind_ == FrictionLawKind::kDisc) return disc_max_step(q / a.x(), d / a.x());
      return disc_max_step(to_law_frame(q).cwiseQuotient(a), to_law_frame(d).cwiseQuotient(a));
    }
    case FrictionLawKind::kRegularPolygon:
    case FrictionLawKind::kPolygon:
    case FrictionLawKind::kEllipsePolygon: {
      double alpha = kInf;
      for (std::size_t j = 0; j < normals_.size(); ++j) {
        const double rate = normals_[j].dot(d);
        if (rate > 0.0) alpha = std::min(alpha, std::max(0.0, (s * heights_[j] - normals_[j].dot(q)) / rate));
      }
      return alpha;
    }
  }
  unknown_kind(kind_, "max_step");
}

double FrictionLaw::boundary_offset(const Eigen::Vector2d& q, double s) const {
  if (zero_ || s <= 0.0) return q.norm();
  switch (kind_) {
    case FrictionLawKind::kInterval:
      return std::max(q.x() - s * mu_vertices_[1], -s * mu_vertices_[0] - q.x());
    case FrictionLawKind::kDisc:
      return q.norm() - s * semi_axes_.x();
    case FrictionLawKind::kEllipse:
      return (to_law_frame(q).cwiseQuotient(semi_axes_).norm() - s) * min_coefficient_;
    case FrictionLawKind::kRegularPolygon:
    case FrictionLawKind::kPolygon:
    case FrictionLawKind::kEllipsePolygon: {
      double offset = -std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < normals_.size(); ++j)
        offset = std::max(offset, normals_[j].dot(q) - s * heights_[j]);
      return offset;
    }
  }
  unknown_kind(kind_, "boundary_offset");
}

FaceLocation FrictionLaw::locate(const Eigen::Vector2d& q, double s, double tolerance) const {
  if (zero_ || s * max_coefficient_ <= tolerance) return {FrictionFace::kDegenerate, -1};
  if (!is_polygonal())
    return boundary_offset(q, s) >= -tolerance ? FaceLocation{FrictionFace::kSmooth, -1}
                                               : FaceLocation{FrictionFace::kInterior, -1};
  // Vertices first: a point within `tolerance` of a corner is at the corner, whatever edge it
  // is nearest to.
  const int n = static_cast<int>(vertices_.size());
  int nearest = -1;
  double nearest_d = std::numeric_limits<double>::infinity();
  for (int j = 0; j < n; ++j) {
    const double dj = (q - s * vertices_[static_cast<std::size_t>(j)]).norm();
    if (dj < nearest_d) {
      nearest_d = dj;
      nearest = j;
    }
  }
  if (nearest_d <= tolerance) return {FrictionFace::kVertex, nearest};
  if (kind_ == FrictionLawKind::kInterval) return {FrictionFace::kInterior, -1};
  int edge = -1;
  double edge_offset = -std::numeric_limits<double>::infinity();
  for (int j = 0; j < n; ++j) {
    const double off = normals_[static_cast<std::size_t>(j)].dot(q) - s * heights_[static_cast<std::size_t>(j)];
    if (off > edge_offset) {
      edge_offset = off;
      edge = j;
    }
  }
  if (edge_offset >= -tolerance) return {FrictionFace::kEdge, edge};
  return {FrictionFace::kInterior, -1};
}

FaceLocation FrictionLaw::sector(const Eigen::Vector2d& u, double angle_tolerance) const {
  if (u.isZero(0.0)) return {FrictionFace::kInterior, -1};
  if (zero_) return {FrictionFace::kDegenerate, -1};
  if (!is_polygonal()) return {FrictionFace::kSmooth, -1};
  if (kind_ == FrictionLawKind::kInterval)
    return u.x() > 0.0 ? FaceLocation{FrictionFace::kVertex, 1}
                       : FaceLocation{FrictionFace::kVertex, 0};
  const int n = static_cast<int>(vertices_.size());
  int best = 0;
  for (int j = 1; j < n; ++j)
    if (vertices_[static_cast<std::size_t>(j)].dot(u) > vertices_[static_cast<std::size_t>(best)].dot(u)) best = j;
  // u exposes vertex `best`; it exposes an edge adjacent to it when it lies on that edge's
  // normal ray (within the angle tolerance).
  const double nu = u.norm();
  for (int edge : {(best - 1 + n) % n, best}) {
    const Eigen::Vector2d& e = normals_[static_cast<std::size_t>(edge)];
    if (e.dot(u) > 0.0 && std::abs(cross(e, u)) <= angle_tolerance * nu)
      return {FrictionFace::kEdge, edge};
  }
  return {FrictionFace::kVertex, best};
}

FrictionClassification FrictionLaw::classify(const Eigen::Vector2d& q, double s,
                                             const Eigen::Vector2d& u,
                                             const ClassificationTolerance& tolerance) const {
  FrictionClassification result;
  result.force = locate(q, s, tolerance.force);
  if (u.norm() <= tolerance.slip)
    result.slip = {FrictionFace::kInterior, -1};
  else
    result.slip = sector(u, tolerance.angle);
  return result;
}

std::string FrictionLaw::describe() const {
  std::ostringstream out;
  out.precision(6);
  out << to_string(kind_) << '(';
  switch (kind_) {
    case FrictionLawKind::kInterval:
      out << "mu_minus=" << mu_vertices_[0] << ", mu_plus=" << mu_vertices_[1];
      break;
    case FrictionLawKind::kDisc:
      out << "mu=" << semi_axes_.x();
      break;
    case FrictionLawKind::kEllipse:
      out << "mu_x=" << semi_axes_.x() << ", mu_y=" << semi_axes_.y();
      break;
    case FrictionLawKind::kRegularPolygon:
      out << "mu=" << mu_vertices_.front() << ", n=" << vertices_.size();
      break;
    case FrictionLawKind::kEllipsePolygon:
      out << "mu_x=" << semi_axes_.x() << ", mu_y=" << semi_axes_.y() << ", n=" << vertices_.size();
      break;
    case FrictionLawKind::kPolygon:
      out << "n=" << mu_vertices_.size() << ", mu=[";
      for (std::size_t j = 0; j < mu_vertices_.size(); ++j) out << (j ? ", " : "") << mu_vertices_[j];
      out << ']';
      break;
  }
  if (orientation_ != 0.0) out << ", orientation_deg=" << orientation_ * 180.0 / std::numbers::pi;
  out << ')';
  return out.str();
}

}  // namespace frictopt::contact
