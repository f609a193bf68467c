// SPDX-License-Identifier: MIT
// Random dual contact QPs for the contact tests, and an independent oracle: projected
// Gauss–Seidel over nodes (block coordinate descent), run to high accuracy.
#pragma once

#include <Eigen/Eigenvalues>
#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

#include "frictopt/contact/friction_law.hpp"

namespace frictopt::contact::testing {

inline constexpr std::uint64_t kSeed = 20261121;

/// SPD matrix BᵀB/n + shift·I with Gaussian B: eigenvalues in ≈ [shift, 4 + shift].
inline Eigen::MatrixXd random_spd(Eigen::Index n, std::mt19937_64& rng, double shift = 0.5) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd b(n, n);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i) b(i, j) = normal(rng);
  Eigen::MatrixXd m = b.transpose() * b / static_cast<double>(n);
  m.diagonal().array() += shift;
  return m;
}

/// Linear term with tangential loads N(0, 0.4²) and normal terms: 60% of nodes pressed
/// (c_ν < 0), the rest lifted (c_ν > 0), so contact, separation, stick and slip all occur.
inline Eigen::VectorXd random_c(int dim, Eigen::Index p, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  Eigen::VectorXd c(dim * p);
  for (Eigen::Index i = 0; i < p; ++i) {
    for (int k = 0; k < dim - 1; ++k) c(dim * i + k) = 0.4 * normal(rng);
    c(dim * i + dim - 1) = (uni(rng) < 0.6 ? -1.0 : 0.5) * (0.2 + uni(rng));
  }
  return c;
}

inline Eigen::Vector2d tangential(const Eigen::VectorXd& v, int dim, Eigen::Index i) {
  return dim == 3 ? Eigen::Vector2d(v(3 * i), v(3 * i + 1)) : Eigen::Vector2d(v(2 * i), 0.0);
}

/// ½zᵀMz + cᵀz.
inline double objective(const Eigen::MatrixXd& m, const Eigen::VectorXd& c, const Eigen::VectorXd& z) {
  return 0.5 * z.dot(m * z) + c.dot(z);
}

/// Projected Gauss–Seidel: for each node in turn, minimize exactly over its block (λ by its
/// closed form, q by projected gradient on the 2×2 block, alternated to convergence) with the
/// other nodes fixed. Block coordinate descent on a strictly convex QP with separable
/// constraints converges to the unique minimizer; we sweep until no entry moves by more than
/// 1e-15 relative (or 20000 sweeps).
inline Eigen::VectorXd projected_gauss_seidel(const Eigen::MatrixXd& m, const Eigen::VectorXd& c,
                                              const Eigen::VectorXd& s,
                                              const std::vector<FrictionLaw>& laws, int dim) {
  const Eigen::Index p = s.size();
  Eigen::VectorXd z = Eigen::VectorXd::Zero(dim * p);
  auto law = [&](Eigen::Index i) -> const FrictionLaw& { return laws.size() == 1 ? laws[0] : laws[i]; };
  for (int sweep = 0; sweep < 20000; ++sweep) {
    double change = 0.0;
    for (Eigen::Index i = 0; i < p; ++i) {
      const Eigen::Index b = dim * i, kn = b + dim - 1;
      const Eigen::VectorXd old = z.segment(b, dim);
      const Eigen::MatrixXd mii = m.block(b, b, dim, dim);
      // Local linear term: r = (Mz + c)_i − M_ii z_i.
      const Eigen::VectorXd r = m.middleRows(b, dim) * z + c.segment(b, dim) - mii * old;
      const int nt = dim - 1;
      const Eigen::MatrixXd mtt = mii.topLeftCorner(nt, nt);
      const double step = 1.0 / mtt.eigenvalues().real().maxCoeff();
      for (int inner = 0; inner < 200; ++inner) {
        const Eigen::VectorXd before = z.segment(b, dim);
        // λ given q: minimize ½M_νν λ² + λ(r_ν + M_νt q).
        const double lin = r(nt) + mii.row(nt).head(nt).dot(z.segment(b, nt));
        z(kn) = std::max(0.0, -lin / mii(nt, nt));
        // q given λ: projected gradient steps of length 1/‖M_tt‖ (converges for convex QP).
        for (int pg = 0; pg < 200; ++pg) {
          const Eigen::VectorXd gq = mtt * z.segment(b, nt) + mii.col(nt).head(nt) * z(kn) + r.head(nt);
          Eigen::Vector2d q = tangential(z, dim, i);
          Eigen::Vector2d g2 = dim == 3 ? Eigen::Vector2d(gq(0), gq(1)) : Eigen::Vector2d(gq(0), 0.0);
          q = law(i).project(q - step * g2, s(i));
          const Eigen::VectorXd prev = z.segment(b, nt);
          z(b) = q.x();
          if (dim == 3) z(b + 1) = q.y();
          if ((z.segment(b, nt) - prev).norm() <= 1e-16 * (1.0 + z.segment(b, nt).norm())) break;
        }
        if ((z.segment(b, dim) - before).norm() <= 1e-16 * (1.0 + before.norm())) break;
      }
      change = std::max(change, (z.segment(b, dim) - old).norm());
    }
    if (change <= 1e-15 * (1.0 + z.norm())) break;
  }
  return z;
}

}  // namespace frictopt::contact::testing
