// SPDX-License-Identifier: MIT
// Friction laws: projections against independent optimality certificates and brute force,
// support functions, validation messages, sector/face classification, n-gon convergence.
#include "frictopt/contact/friction_law.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "frictopt/core/error.hpp"

namespace frictopt::contact {
namespace {

constexpr std::uint64_t kSeed = 20261121;
constexpr double kEps = std::numeric_limits<double>::epsilon();

std::vector<FrictionLaw> all_3d_laws() {
  return {FrictionLaw::disc(0.4),
          FrictionLaw::regular_polygon(0.4, 8),
          FrictionLaw::regular_polygon(0.3, 3),
          FrictionLaw::polygon({0.3, 0.5, 0.3, 0.5}),
          FrictionLaw::polygon({0.2, 0.35, 0.5, 0.45, 0.3, 0.25}),
          FrictionLaw::ellipse(0.2, 0.6),
          FrictionLaw::ellipse_polygon(0.2, 0.6, 16)};
}

/// Dense samples of the boundary of W (s = 1): polygon edges, or the parametrized curve.
std::vector<Eigen::Vector2d> boundary_samples(const FrictionLaw& law, int count) {
  std::vector<Eigen::Vector2d> pts;
  if (law.is_polygonal()) {
    const auto v = law.vertices();
    const int n = static_cast<int>(v.size());
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < count / n; ++k) {
        const double t = static_cast<double>(k) / (count / n);
        pts.push_back((1 - t) * v[j] + t * v[(j + 1) % n]);
      }
  } else {
    const Eigen::Vector2d a = law.semi_axes();
    for (int k = 0; k < count; ++k) {
      const double th = 2 * std::numbers::pi * k / count;
      pts.emplace_back(a.x() * std::cos(th), a.y() * std::sin(th));
    }
  }
  return pts;
}

TEST(FrictionLawKind, StringsRoundTripThroughOneTable) {
  for (auto kind : {FrictionLawKind::kInterval, FrictionLawKind::kDisc,
                    FrictionLawKind::kRegularPolygon, FrictionLawKind::kPolygon,
                    FrictionLawKind::kEllipse, FrictionLawKind::kEllipsePolygon})
    EXPECT_EQ(parse_friction_law_kind(to_string(kind)), kind);
  for (auto face : {FrictionFace::kInterior, FrictionFace::kEdge, FrictionFace::kVertex,
                    FrictionFace::kSmooth, FrictionFace::kDegenerate})
    EXPECT_EQ(parse_friction_face(to_string(face)), face);
  EXPECT_THROW((void)parse_friction_law_kind("hexagon"), InvalidInput);
}

TEST(FrictionLaw, ThesisPolygonHasVerticesOnTheCircleAtOddMultiplesOfPiOverN) {
  const int n = 4;
  const auto law = FrictionLaw::regular_polygon(0.5, n);
  ASSERT_EQ(law.vertices().size(), 4u);
  for (int j = 0; j < n; ++j) {
    const double phi = std::numbers::pi * (2 * j + 1) / n;  // thesis φ_{j+1}
    EXPECT_NEAR(law.vertices()[j].x(), 0.5 * std::cos(phi), 4 * kEps);
    EXPECT_NEAR(law.vertices()[j].y(), 0.5 * std::sin(phi), 4 * kEps);
    // Edge j normal at angle 2π(j+1)/n, height μ cos(π/n) (docs/theory/state-problem.md §3).
    const double psi = 2 * std::numbers::pi * (j + 1) / n;
    EXPECT_NEAR(law.edge_normals()[j].x(), std::cos(psi), 8 * kEps);
    EXPECT_NEAR(law.edge_normals()[j].y(), std::sin(psi), 8 * kEps);
    EXPECT_NEAR(law.edge_heights()[j], 0.5 * std::cos(std::numbers::pi / n), 8 * kEps);
  }
}

TEST(FrictionLaw, AnisotropicRhombusEdgeDataMatchesRemark621) {
  const double f1 = 0.3, f2 = 0.7;
  const auto law = FrictionLaw::polygon({f1, f2, f1, f2});
  const Eigen::Vector2d e1 = Eigen::Vector2d(f2 - f1, f1 + f2).normalized();
  EXPECT_LT((law.edge_normals()[0] - e1).norm(), 8 * kEps);
  for (double h : law.edge_heights()) EXPECT_NEAR(h, f1 * f2 / std::hypot(f1, f2), 8 * kEps);
  // Sliding along v_1 costs F1, along v_2 costs F2.
  EXPECT_NEAR(law.support(Eigen::Vector2d(1, 1).normalized()), f1, 4 * kEps);
  EXPECT_NEAR(law.support(Eigen::Vector2d(-1, 1).normalized()), f2, 4 * kEps);
}

// The projection p of q onto the convex set s·W is characterized by p ∈ s·W and
// ⟨q − p, w − p⟩ <= 0 for all w ∈ s·W; for a polygon it suffices to test the vertices, for
// smooth sets we test dense boundary samples. The tolerance 1e-12 (scale 1) is ~100 ulps of the
// products involved.
TEST(FrictionLaw, ProjectionSatisfiesTheVariationalInequalityForEveryLaw) {
  std::mt19937_64 rng{kSeed};
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uni(0.0, 2.0);
  for (const auto& law : all_3d_laws()) {
    const auto samples = boundary_samples(law, 4000);
    for (int trial = 0; trial < 200; ++trial) {
      const double s = uni(rng);
      const Eigen::Vector2d q(normal(rng), normal(rng));
      const Eigen::Vector2d p = law.project(q, s);
      EXPECT_LE(law.boundary_offset(p, s), 1e-14) << law.describe() << " q=" << q.transpose();
      double worst = -std::numeric_limits<double>::infinity();
      for (const auto& w : samples) worst = std::max(worst, (q - p).dot(s * w - p));
      EXPECT_LE(worst, 1e-12) << law.describe() << " seed " << kSeed << " trial " << trial;
      // Brute force: no boundary sample is closer than p, up to the sample spacing.
      double brute = std::numeric_limits<double>::infinity();
      for (const auto& w : samples) brute = std::min(brute, (q - s * w).norm());
      if (law.boundary_offset(q, s) > 0) {
        const double spacing = 2 * std::numbers::pi * law.max_coefficient() * s / 4000 * 2;
        EXPECT_LE((q - p).norm(), brute + 1e-14) << law.describe();
        EXPECT_GE((q - p).norm(), brute - spacing) << law.describe();
      } else {
        EXPECT_EQ(p, q);
      }
    }
  }
}

TEST(FrictionLaw, IntervalProjectionClampsToDirectionDependentBounds) {
  const auto law = FrictionLaw::interval(0.2, 0.5);
  EXPECT_EQ(law.dim(), 2);
  EXPECT_DOUBLE_EQ(law.project(3.0, 2.0), 1.0);
  EXPECT_DOUBLE_EQ(law.project(-3.0, 2.0), -0.4);
  EXPECT_DOUBLE_EQ(law.project(0.1, 2.0), 0.1);
  EXPECT_DOUBLE_EQ(law.support(2.0), 1.0);
  EXPECT_DOUBLE_EQ(law.support(-2.0), 0.4);
  EXPECT_EQ(law.sector(Eigen::Vector2d(1, 0), 1e-8), (FaceLocation{FrictionFace::kVertex, 1}));
  EXPECT_EQ(law.locate(Eigen::Vector2d(-0.4, 0), 2.0, 1e-12),
            (FaceLocation{FrictionFace::kVertex, 0}));
}

TEST(FrictionLaw, SupportIsMaxOverVerticesAndAttainedAtExposedPoint) {
  std::mt19937_64 rng{kSeed + 1};
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const auto& law : all_3d_laws()) {
    const auto samples = boundary_samples(law, 20000);
    for (int trial = 0; trial < 100; ++trial) {
      const Eigen::Vector2d u(normal(rng), normal(rng));
      double best = -std::numeric_limits<double>::infinity();
      for (const auto& w : samples) best = std::max(best, w.dot(u));
      const double n_w = law.support(u);
      // Polygons: the vertices are among the samples, so equality to rounding. Smooth sets:
      // the sampled max is below by at most |u|·μ_max·(1 − cos(π/20000)) ~ 1.2e-8 relative.
      const double tol = law.is_polygonal() ? 8 * kEps * u.norm() : 2e-8 * u.norm();
      EXPECT_NEAR(n_w, best, tol) << law.describe();
      EXPECT_GE(n_w, best - 8 * kEps * u.norm());
      const Eigen::Vector2d w = law.exposed_point(u);
      EXPECT_NEAR(w.dot(u), n_w, 8 * kEps * u.norm() * law.max_coefficient());
      EXPECT_LE(law.boundary_offset(w, 1.0), 1e-15);
    }
  }
}

TEST(FrictionLaw, PolygonValidationNamesTheOffendingVertex) {
  auto message_of = [](auto&& make) {
    try {
      make();
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message_of([] { (void)FrictionLaw::polygon({0.3, 0.3}); }).find("n = 2; expected n >= 3"),
            std::string::npos);
  EXPECT_NE(message_of([] { (void)FrictionLaw::regular_polygon(0.3, 2); }).find("n = 2"),
            std::string::npos);
  EXPECT_NE(message_of([] { (void)FrictionLaw::polygon({0.3, -0.1, 0.3}); })
                .find("mu[1] = -0.1; expected a finite value >= 0"),
            std::string::npos);
  EXPECT_NE(message_of([] { (void)FrictionLaw::polygon({0.3, 0.0, 0.3, 0.3}); }).find("mu[1] = 0"),
            std::string::npos);
  // Hexagon with vertex 1 pulled inside the chord of its neighbours: reflex.
  const std::string reflex = message_of([] { (void)FrictionLaw::polygon({1, 0.2, 1, 1, 1, 1}); });
  EXPECT_NE(reflex.find("vertex 1"), std::string::npos) << reflex;
  EXPECT_NE(reflex.find("reflex"), std::string::npos) << reflex;
  EXPECT_NE(reflex.find("mu[1] = 0.2"), std::string::npos) << reflex;
  // Vertex 1 exactly on the chord (y = 1/2): collinear, not a corner.
  const std::string flat = message_of([] { (void)FrictionLaw::polygon({1, 0.5, 1, 1, 1, 1}); });
  EXPECT_NE(flat.find("vertex 1"), std::string::npos) << flat;
  EXPECT_NE(flat.find("collinear"), std::string::npos) << flat;
  EXPECT_NE(message_of([] { (void)FrictionLaw::ellipse(0.3, 0.0); }).find("mu_y = 0"),
            std::string::npos);
  EXPECT_THROW((void)FrictionLaw::disc(-1.0), InvalidInput);
  EXPECT_THROW((void)FrictionLaw::interval(std::nan(""), 0.1), InvalidInput);
  // All-zero coefficients are the frictionless law.
  const auto zero = FrictionLaw::polygon({0, 0, 0, 0});
  EXPECT_TRUE(zero.is_zero());
  EXPECT_EQ(zero.project(Eigen::Vector2d(1, 2), 3.0), Eigen::Vector2d::Zero());
}

TEST(FrictionLaw, LocateAndSectorIdentifyEdgesAndVertices) {
  const int n = 6;
  const auto law = FrictionLaw::regular_polygon(0.5, n);
  const double s = 2.0, tol = 1e-12;
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector2d wj = law.vertices()[j], wk = law.vertices()[(j + 1) % n];
    EXPECT_EQ(law.locate(s * wj, s, tol), (FaceLocation{FrictionFace::kVertex, j}));
    EXPECT_EQ(law.locate(s * (0.3 * wj + 0.7 * wk), s, tol), (FaceLocation{FrictionFace::kEdge, j}));
    EXPECT_EQ(law.locate(0.5 * s * wj, s, tol), (FaceLocation{FrictionFace::kInterior, -1}));
    // A slip direction along v_j is in sector j; along the edge normal e_j on ray j.
    EXPECT_EQ(law.sector(wj, 1e-8), (FaceLocation{FrictionFace::kVertex, j}));
    EXPECT_EQ(law.sector(3.0 * law.edge_normals()[j], 1e-8), (FaceLocation{FrictionFace::kEdge, j}));
    const auto c = law.classify(s * wj, s, wj, {tol, 1e-12, 1e-8});
    EXPECT_EQ(c.force, (FaceLocation{FrictionFace::kVertex, j}));
    EXPECT_EQ(c.slip, (FaceLocation{FrictionFace::kVertex, j}));
  }
  EXPECT_EQ(law.locate(Eigen::Vector2d(1e-13, 0), 0.0, tol).face, FrictionFace::kDegenerate);
  const auto disc = FrictionLaw::disc(0.5);
  EXPECT_EQ(disc.locate(Eigen::Vector2d(0.6, 0.8), 2.0, tol).face, FrictionFace::kSmooth);
  EXPECT_EQ(disc.classify(Eigen::Vector2d(0.1, 0), 2.0, Eigen::Vector2d::Zero(), {tol, 0, 1e-8})
                .slip.face,
            FrictionFace::kInterior);
}

TEST(FrictionLaw, MaxStepLandsOnTheBoundary) {
  std::mt19937_64 rng{kSeed + 2};
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const auto& law : all_3d_laws()) {
    for (int trial = 0; trial < 100; ++trial) {
      const double s = 1.5;
      const Eigen::Vector2d q = 0.5 * law.project(Eigen::Vector2d(normal(rng), normal(rng)), s);
      const Eigen::Vector2d d(normal(rng), normal(rng));
      const double alpha = law.max_step(q, s, d);
      ASSERT_TRUE(std::isfinite(alpha));
      // Offset is exact (or of distance scale for the ellipse): |offset| ~ rounding of q + αd.
      EXPECT_NEAR(law.boundary_offset(q + alpha * d, s), 0.0, 1e-14) << law.describe();
    }
  }
}

struct ConvergenceRates {
  std::vector<double> distance;    ///< rates of max |dist(q, W_n) − dist(q, W)|
  std::vector<double> support;     ///< rates of max |N_{W_n}(u) − N_W(u)| over unit u
  std::vector<double> projection;  ///< rates of max |P_n(q) − P(q)|
};

/// Errors of the n-gon law against the exact smooth law over random points outside (radius
/// 1.5, s = 1), for n = 8, 16, 32, 64; returns the observed rates log2(E(n)/E(2n)).
ConvergenceRates observed_rates(const FrictionLaw& exact, auto make_polygon, const char* name) {
  std::mt19937_64 rng{kSeed + 3};
  std::uniform_real_distribution<double> angle(0.0, 2 * std::numbers::pi);
  std::vector<Eigen::Vector2d> qs;
  for (int k = 0; k < 4000; ++k) {
    const double a = angle(rng);
    qs.emplace_back(1.5 * std::cos(a), 1.5 * std::sin(a));
  }
  std::vector<double> e_dist, e_supp, e_proj;
  for (int n : {8, 16, 32, 64}) {
    const FrictionLaw poly = make_polygon(n);
    double ed = 0, es = 0, ep = 0;
    for (const auto& q : qs) {
      const Eigen::Vector2d pn = poly.project(q, 1.0), p = exact.project(q, 1.0);
      ep = std::max(ep, (pn - p).norm());
      ed = std::max(ed, std::abs((q - pn).norm() - (q - p).norm()));
      es = std::max(es, std::abs(poly.support(q.normalized()) - exact.support(q.normalized())));
    }
    e_dist.push_back(ed);
    e_supp.push_back(es);
    e_proj.push_back(ep);
    std::cout << "[ n-gon convergence ] " << name << " n=" << n << "  max|dist err| = " << ed
              << "  max|support err| = " << es << "  max|P_n(q) - P(q)| = " << ep << '\n';
  }
  auto rates = [](const std::vector<double>& e) {
    std::vector<double> r;
    for (std::size_t k = 0; k + 1 < e.size(); ++k) r.push_back(std::log2(e[k] / e[k + 1]));
    return r;
  };
  return {rates(e_dist), rates(e_supp), rates(e_proj)};
}

// The n-gon's boundary is within μ(1 − cos(π/n)) = O(1/n²) of the curve (Hausdorff distance),
// so distances to the set and the support function converge at second order. The projected
// point itself converges only at first order for points at a fixed distance outside: every q in
// the normal cone of a vertex (angular width ~2π/n) projects to that vertex, while the exact
// projection moves along the arc, an error ~ μ·π/n. Observed rates are checked within 10%
// (the sampled maxima miss the worst direction by at most 2π/4000 in angle).
TEST(FrictionLaw, PolygonLawConvergesToDiscAndEllipse) {
  const auto disc = observed_rates(FrictionLaw::disc(0.5),
                                   [](int n) { return FrictionLaw::regular_polygon(0.5, n); }, "disc");
  const auto ell = observed_rates(FrictionLaw::ellipse(0.3, 0.7),
                                  [](int n) { return FrictionLaw::ellipse_polygon(0.3, 0.7, n); },
                                  "ellipse");
  for (const auto* r : {&disc, &ell}) {
    for (double x : r->distance) EXPECT_NEAR(x, 2.0, 0.2);
    for (double x : r->support) EXPECT_NEAR(x, 2.0, 0.2);
    for (double x : r->projection) EXPECT_NEAR(x, 1.0, 0.1);
  }
}

}  // namespace
}  // namespace frictopt::contact
