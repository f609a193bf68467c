// SPDX-License-Identifier: MIT
// TEST19 of Lukšan & Vlček (TR V-798, 2000): all 25 small unconstrained nonsmooth problems
// (TR48's data, which the Fortran reads from TEST19.DAT, in luksan_vlcek_tr48_data.cpp). Formulas
// follow the report; data and starting points follow the Fortran (TIUD19, TFFU19), which the report's
// tables were computed with. Where several pieces of a max tie, the gradient of the first one in
// the order listed is returned (one Clarke subgradient).
#include <cmath>
#include <limits>
#include <numbers>

#include "testset/luksan_vlcek.hpp"
#include "luksan_vlcek_pieces.hpp"
#include "luksan_vlcek_tr48_data.hpp"

namespace frictopt::optim {

namespace {

using Eigen::VectorXd;
using detail::Ad;
using detail::AdVector;
using detail::ad_abs;
using detail::ad_hypot;
using detail::ad_max;
using detail::constant;
using detail::make;
using detail::MaxOf;
using detail::sgn;
using detail::success;
using detail::variables;
using detail::Vec;
using detail::vec;

// Maxquad data (TEST19 #16): A_k symmetric 10×10, b_k, k = 1..5.
struct MaxquadData {
  std::vector<Eigen::MatrixXd> A;
  std::vector<VectorXd> b;
  MaxquadData() {
    const int n = 10;
    for (int k = 1; k <= 5; ++k) {
      Eigen::MatrixXd a(n, n);
      VectorXd bk(n);
      for (int i = 1; i <= n; ++i) {
        for (int j = i + 1; j <= n; ++j) {
          a(i - 1, j - 1) = std::exp(static_cast<double>(i) / j) * std::cos(static_cast<double>(i * j)) * std::sin(static_cast<double>(k));
          a(j - 1, i - 1) = a(i - 1, j - 1);
        }
      }
      for (int i = 1; i <= n; ++i) {
        bk(i - 1) = std::exp(static_cast<double>(i) / k) * std::sin(static_cast<double>(i * k));
        double d = std::abs(std::sin(static_cast<double>(k))) * i / n;
        for (int j = 1; j <= n; ++j)
          if (j != i) d += std::abs(a(i - 1, j - 1));
        a(i - 1, i - 1) = d;
      }
      A.push_back(a);
      b.push_back(bk);
    }
  }
};

// Colville 1 / Shell dual data (TEST19 #13, #25): the Fortran's array CC with Y(3) = −3.5,
// Y(45) = −2.8, Y(53) = −0.25; A is 10×5 (column-major in Y), C 5×5 symmetric.
struct ColvilleData {
  Eigen::Matrix<double, 10, 5> A;
  Eigen::Matrix<double, 10, 1> b;
  Eigen::Matrix<double, 5, 5> C;
  Eigen::Matrix<double, 5, 1> d, e;
};

const ColvilleData& colville_data() {
  static const ColvilleData data = [] {
    ColvilleData c;
    c.A << -16, 2, 0, 1, 0,  0, -2, 0, 4, 2,  -3.5, 0, 2, 0, 0,  0, -2, 0, -4, -1,  0, -9, -2, 1, -2.8,
        2, 0, -4, 0, 0,  -1, -1, -1, -1, -1,  -1, -2, -3, -2, -1,  1, 2, 3, 4, 5,  1, 1, 1, 1, 1;
    c.b << -40, -2, -0.25, -4, -4, -1, -40, -60, 5, 1;
    c.C << 30, -20, -10, 32, -10,  -20, 39, -6, -31, 32,  -10, -6, 10, -6, -10,  32, -31, -6, 39, -20,
        -10, 32, -10, -20, 30;
    c.d << 4, 8, 10, 6, 2;
    c.e << -15, -27, -36, -18, -12;
    return c;
  }();
  return data;
}

}  // namespace

std::vector<LuksanVlcekProblem> luksan_vlcek_unconstrained() {
  std::vector<LuksanVlcekProblem> P;
  P.push_back(make("Rosenbrock", "TEST19 #1", vec({-1.2, 1.0}), 0.0, [](Vec x) {
    const double a = x(1) - x(0) * x(0);
    return OracleResult::success(100 * a * a + std::pow(1 - x(0), 2),
                                 vec({-400 * x(0) * a - 2 * (1 - x(0)), 200 * a}));
  }));
  P.push_back(make("Crescent", "TEST19 #2", vec({-1.5, 2.0}), 0.0, [](Vec x) {
    // max{x1² + (x2−1)² + x2 − 1, −x1² − (x2−1)² + x2 + 1} = x2 + |x1² + (x2−1)² − 1|
    const double t = x(0) * x(0) + std::pow(x(1) - 1, 2) - 1;
    const double s = sgn(t);
    return OracleResult::success(x(1) + std::abs(t), vec({2 * s * x(0), 2 * s * (x(1) - 1) + 1}));
  }));
  P.push_back(make("CB2", "TEST19 #3", vec({1.0, -0.1}), 1.9522245, [](Vec x) {
    MaxOf m;
    m.add(x(0) * x(0) + std::pow(x(1), 4), vec({2 * x(0), 4 * std::pow(x(1), 3)}));
    m.add(std::pow(2 - x(0), 2) + std::pow(2 - x(1), 2), vec({-2 * (2 - x(0)), -2 * (2 - x(1))}));
    const double e = 2 * std::exp(x(1) - x(0));
    m.add(e, vec({-e, e}));
    return OracleResult::success(m.f, m.g);
  }));
  P.push_back(make("CB3", "TEST19 #4", vec({2.0, 2.0}), 2.0, [](Vec x) {
    MaxOf m;
    m.add(std::pow(x(0), 4) + x(1) * x(1), vec({4 * std::pow(x(0), 3), 2 * x(1)}));
    m.add(std::pow(2 - x(0), 2) + std::pow(2 - x(1), 2), vec({-2 * (2 - x(0)), -2 * (2 - x(1))}));
    const double e = 2 * std::exp(x(1) - x(0));
    m.add(e, vec({-e, e}));
    return OracleResult::success(m.f, m.g);
  }));
  P.push_back(make("DEM", "TEST19 #5", vec({1.0, 1.0}), -3.0, [](Vec x) {
    MaxOf m;
    m.add(5 * x(0) + x(1), vec({5, 1}));
    m.add(-5 * x(0) + x(1), vec({-5, 1}));
    m.add(x(0) * x(0) + x(1) * x(1) + 4 * x(1), vec({2 * x(0), 2 * x(1) + 4}));
    return OracleResult::success(m.f, m.g);
  }));
  P.push_back(make("QL", "TEST19 #6", vec({-1.0, 5.0}), 7.2, [](Vec x) {
    MaxOf m;
    const double f1 = x(0) * x(0) + x(1) * x(1);
    m.add(f1, vec({2 * x(0), 2 * x(1)}));
    m.add(f1 + 10 * (-4 * x(0) - x(1) + 4), vec({2 * x(0) - 40, 2 * x(1) - 10}));
    m.add(f1 + 10 * (-x(0) - 2 * x(1) + 6), vec({2 * x(0) - 10, 2 * x(1) - 20}));
    return OracleResult::success(m.f, m.g);
  }));
  P.push_back(make("LQ", "TEST19 #7", vec({-0.5, -0.5}), -std::numbers::sqrt2, [](Vec x) {
    MaxOf m;
    m.add(-x(0) - x(1), vec({-1, -1}));
    m.add(-x(0) - x(1) + x(0) * x(0) + x(1) * x(1) - 1, vec({2 * x(0) - 1, 2 * x(1) - 1}));
    return OracleResult::success(m.f, m.g);
  }));
  P.push_back(make("Mifflin1", "TEST19 #8", vec({0.8, 0.6}), -1.0, [](Vec x) {
    const double t = x(0) * x(0) + x(1) * x(1) - 1;
    if (t >= 0) return OracleResult::success(-x(0) + 20 * t, vec({40 * x(0) - 1, 40 * x(1)}));
    return OracleResult::success(-x(0), vec({-1, 0}));
  }));
  P.push_back(make("Mifflin2", "TEST19 #9", vec({-1.0, -1.0}), -1.0, [](Vec x) {
    const double t = x(0) * x(0) + x(1) * x(1) - 1;
    const double c = 4 + 3.5 * sgn(t);  // d/dx of 2t + 1.75|t| is (2 ± 1.75)·2x
    return OracleResult::success(-x(0) + 2 * t + 1.75 * std::abs(t), vec({c * x(0) - 1, c * x(1)}));
  }));
  P.push_back(make("Wolfe", "TEST19 #10", vec({3.0, 2.0}), -8.0, [](Vec x) {
    if (x(0) > std::abs(x(1))) {
      const double r = std::sqrt(9 * x(0) * x(0) + 16 * x(1) * x(1));
      return OracleResult::success(5 * r, vec({45 * x(0) / r, 80 * x(1) / r}));
    }
    if (x(0) > 0) return OracleResult::success(9 * x(0) + 16 * std::abs(x(1)), vec({9, 16 * sgn(x(1))}));
    return OracleResult::success(9 * x(0) + 16 * std::abs(x(1)) - std::pow(x(0), 9),
                                 vec({9 - 9 * std::pow(x(0), 8), 16 * sgn(x(1))}));
  }));
  P.push_back(make("Rosen-Suzuki", "TEST19 #11", VectorXd::Zero(4), -44.0, [](Vec x) {
    // f = f1 + 10·max(0, f2, f3, f4) (the Fortran's exact-penalty form).
    const double q = x(0) * x(0) + x(1) * x(1) + x(2) * x(2);
    const double f1 = q + x(2) * x(2) + x(3) * x(3) - 5 * (x(0) + x(1)) - 21 * x(2) + 7 * x(3);
    const VectorXd g1 = vec({2 * x(0) - 5, 2 * x(1) - 5, 4 * x(2) - 21, 2 * x(3) + 7});
    MaxOf m;
    m.add(0.0, VectorXd::Zero(4));
    m.add(q + x(3) * x(3) + x(0) - x(1) + x(2) - x(3) - 8,
          vec({2 * x(0) + 1, 2 * x(1) - 1, 2 * x(2) + 1, 2 * x(3) - 1}));
    m.add(q + x(1) * x(1) + 2 * x(3) * x(3) - x(0) - x(3) - 10,
          vec({2 * x(0) - 1, 4 * x(1), 2 * x(2), 4 * x(3) - 1}));
    m.add(q + 2 * x(0) - x(1) - x(3) - 5, vec({2 * x(0) + 2, 2 * x(1) - 1, 2 * x(2), -1}));
    return OracleResult::success(f1 + 10 * m.f, g1 + 10 * m.g);
  }));
  P.push_back(make("Shor", "TEST19 #12", vec({0, 0, 0, 0, 1}), 22.600162, [](Vec x) {
    static const double a[10][5] = {{0, 0, 0, 0, 0}, {2, 1, 1, 1, 3}, {1, 2, 1, 1, 2}, {1, 4, 1, 2, 2},
                                    {3, 2, 1, 0, 1}, {0, 2, 1, 0, 1}, {1, 1, 1, 1, 1}, {1, 0, 1, 2, 1},
                                    {0, 0, 2, 1, 0}, {1, 1, 2, 0, 0}};
    static const double b[10] = {1, 5, 10, 2, 4, 3, 1.7, 2.5, 6, 3.5};
    MaxOf m;
    for (int i = 0; i < 10; ++i) {
      VectorXd d(5);
      for (int j = 0; j < 5; ++j) d(j) = x(j) - a[i][j];
      m.add(b[i] * d.squaredNorm(), 2 * b[i] * d);
    }
    return OracleResult::success(m.f, m.g);
  }));
  P.push_back(make("Colville1", "TEST19 #13", vec({0, 0, 0, 0, 1}), -32.348679, [](Vec x) {
    // 50·max(0, max_i(b_i − A_i x)) + Σ_j (d_j x_j³ + e_j x_j + (Cx)_j x_j): the exact-penalty
    // form of Colville's problem 1 in the Fortran. Unbounded below (the cubic terms); f* is the
    // local minimum the report lists (testsets pitfall).
    const ColvilleData& c = colville_data();
    const AdVector a = variables(x);
    Ad pen = constant(0.0, 5);
    for (int i = 0; i < 10; ++i) {
      Ad r = constant(c.b(i), 5);
      for (int j = 0; j < 5; ++j) r -= c.A(i, j) * a(j);
      pen = ad_max(pen, r);
    }
    Ad f = 50.0 * pen;
    for (int j = 0; j < 5; ++j) {
      Ad cx = constant(0.0, 5);
      for (int i = 0; i < 5; ++i) cx += c.C(i, j) * a(i);
      f += c.d(j) * a(j) * a(j) * a(j) + c.e(j) * a(j) + cx * a(j);
    }
    return success(f);
  }));
  P.push_back(make("HS78", "TEST19 #14", vec({-2, 1.5, 2, -1, -1}), -2.9197004, [](Vec x) {
    const double prod = x(0) * x(1) * x(2) * x(3) * x(4);
    VectorXd g(5);
    for (int i = 0; i < 5; ++i) {
      double p = 1;
      for (int j = 0; j < 5; ++j)
        if (j != i) p *= x(j);
      g(i) = p;
    }
    const double t1 = x.squaredNorm() - 10;
    const double t2 = x(1) * x(2) - 5 * x(3) * x(4);
    const double t3 = std::pow(x(0), 3) + std::pow(x(1), 3) + 1;
    g += 10 * sgn(t1) * 2 * x;
    g(1) += 10 * sgn(t2) * x(2);
    g(2) += 10 * sgn(t2) * x(1);
    g(3) += -50 * sgn(t2) * x(4);
    g(4) += -50 * sgn(t2) * x(3);
    g(0) += 30 * sgn(t3) * x(0) * x(0);
    g(1) += 30 * sgn(t3) * x(1) * x(1);
    return OracleResult::success(prod + 10 * (std::abs(t1) + std::abs(t2) + std::abs(t3)), g);
  }));
  P.push_back(make("El-Attar", "TEST19 #15", vec({2, 2, 7, 0, -2, 1}), 0.5598131, [](Vec x) {
    double f = 0;
    VectorXd g = VectorXd::Zero(6);
    for (int i = 1; i <= 51; ++i) {
      const double t = (i - 1) / 10.0;
      const double z = 0.5 * std::exp(-t) - std::exp(-2 * t) + 0.5 * std::exp(-3 * t) +
                       1.5 * std::exp(-1.5 * t) * std::sin(7 * t) + std::exp(-2.5 * t) * std::sin(5 * t);
      const double e1 = std::exp(-x(1) * t);
      const double e2 = std::exp(-x(5) * t);
      const double c = std::cos(x(2) * t + x(3));
      const double s = std::sin(x(2) * t + x(3));
      const double r = x(0) * e1 * c + x(4) * e2 - z;
      f += std::abs(r);
      const double sg = sgn(r);
      g(0) += sg * e1 * c;
      g(1) -= sg * e1 * c * x(0) * t;
      g(2) -= sg * e1 * s * x(0) * t;
      g(3) -= sg * e1 * s * x(0);
      g(4) += sg * e2;
      g(5) -= sg * e2 * x(4) * t;
    }
    return OracleResult::success(f, g);
  }));
  P.push_back(make("Maxquad", "TEST19 #16", VectorXd::Ones(10), -0.8414083, [](Vec x) {
    static const MaxquadData data;
    MaxOf m;
    for (int k = 0; k < 5; ++k)
      m.add(x.dot(data.A[static_cast<std::size_t>(k)] * x) - data.b[static_cast<std::size_t>(k)].dot(x),
            2 * data.A[static_cast<std::size_t>(k)] * x - data.b[static_cast<std::size_t>(k)]);
    return OracleResult::success(m.f, m.g);
  }));
  Eigen::VectorXd x_gill = Eigen::VectorXd::Constant(10, -0.1);
  P.push_back(make("Gill", "TEST19 #17", x_gill, 9.7857721, [](Vec x) {
    // max(F1, F2, F3): a penalty term, Watson's polynomial fit (29 points) and a chained
    // Rosenbrock function, each smooth.
    const AdVector a = variables(x);
    const Eigen::Index n = 10;
    Ad sq = constant(-0.25, n);
    for (int i = 0; i < 10; ++i) sq += a(i) * a(i);
    Ad f1 = 1e-3 * sq * sq;
    for (int i = 0; i < 10; ++i) f1 += (a(i) - 1.0) * (a(i) - 1.0);
    Ad f2 = a(0) * a(0) + (a(1) - a(0) * a(0) - 1.0) * (a(1) - a(0) * a(0) - 1.0);
    for (int i = 2; i <= 30; ++i) {
      const double ai = (i - 1) / 29.0;
      Ad p = constant(0.0, n);
      for (int j = 1; j <= 10; ++j) p += a(j - 1) * std::pow(ai, j - 1);
      Ad r = -p * p - 1.0;
      for (int j = 2; j <= 10; ++j) r += a(j - 1) * (j - 1.0) * std::pow(ai, j - 2);
      f2 += r * r;
    }
    Ad f3 = constant(0.0, n);
    for (int i = 1; i < 10; ++i)
      f3 += 100.0 * (a(i) - a(i - 1) * a(i - 1)) * (a(i) - a(i - 1) * a(i - 1)) + (1.0 - a(i)) * (1.0 - a(i));
    return success(ad_max(ad_max(f1, f2), f3));
  }));
  {
    // Steiner 2: a Steiner-tree-like sum of weighted Euclidean distances; x = (abscissae x1..x6,
    // ordinates x7..x12) of six free points; data PP of the Fortran with Y(10) = −0.5.
    static const double ax[6] = {0, 2, 3, 4, 5, 6};
    static const double ay[6] = {2, 3, -1, -0.5, 2, 2};
    static const double w[6] = {2, 1, 1, 5, 1, 1};
    static const double v[5] = {1, 1, 2, 3, 2};
    Eigen::VectorXd x0(12);
    x0(0) = 2.0 / 3.0;
    x0(6) = 5.0 / 3.0;
    for (int i = 1; i <= 4; ++i) {
      x0(i) = (x0(i - 1) + ax[i] + ax[i + 1]) / 3.0;
      x0(i + 6) = (x0(i + 5) + ay[i] + ay[i + 1]) / 3.0;
    }
    x0(5) = (x0(4) + 11.5) / 3.0;
    x0(11) = (x0(10) + 1.0) / 3.0;
    P.push_back(make("Steiner2", "TEST19 #18", x0, 16.703838, [](Vec x) {
      const AdVector a = variables(x);
      Ad f = ad_hypot(a(0), a(6)) + ad_hypot(5.5 - a(5), 1.0 + a(11));
      for (int j = 0; j < 6; ++j) f += w[j] * ad_hypot(ax[j] - a(j), ay[j] - a(6 + j));
      for (int j = 0; j < 5; ++j) f += v[j] * ad_hypot(a(j) - a(j + 1), a(j + 6) - a(j + 7));
      return success(f);
    }));
  }
  VectorXd x20(20);
  for (int i = 1; i <= 10; ++i) {
    x20(i - 1) = i;
    x20(i + 9) = -i - 10;
  }
  P.push_back(make("Maxq", "TEST19 #19", x20, 0.0, [](Vec x) {
    Eigen::Index k = 0;
    const double f = x.array().square().maxCoeff(&k);
    VectorXd g = VectorXd::Zero(x.size());
    g(k) = 2 * x(k);
    return OracleResult::success(f, g);
  }));
  P.push_back(make("Maxl", "TEST19 #20", x20, 0.0, [](Vec x) {
    Eigen::Index k = 0;
    const double f = x.cwiseAbs().maxCoeff(&k);
    VectorXd g = VectorXd::Zero(x.size());
    g(k) = sgn(x(k));
    return OracleResult::success(f, g);
  }));
  P.push_back(make("TR48", "TEST19 #21", VectorXd::Zero(48), -638565.0, [](Vec x) {
    // Σ_j d_j max_i (x_i − a_ij) − Σ_i s_i x_i (transportation dual); subgradient: −s plus d_j
    // at the first maximizing i of each j.
    const detail::Tr48Data& t = detail::tr48_data();
    VectorXd g = -t.s;
    double f = -t.s.dot(x);
    for (Eigen::Index j = 0; j < 48; ++j) {
      Eigen::Index i = 0;
      f += t.d(j) * (x - t.a.col(j)).maxCoeff(&i);
      g(i) += t.d(j);
    }
    return OracleResult::success(f, g);
  }));
  VectorXd x50(50);
  for (int i = 1; i <= 50; ++i) x50(i - 1) = i - 25.5;
  P.push_back(make("Goffin", "TEST19 #22", x50, 0.0, [](Vec x) {
    Eigen::Index k = 0;
    const double mx = x.maxCoeff(&k);
    VectorXd g = VectorXd::Constant(x.size(), -1.0);
    g(k) += 50;
    return OracleResult::success(50 * mx - x.sum(), g);
  }));
  P.push_back(make("MXHILB", "TEST19 #23", VectorXd::Ones(50), 0.0, [](Vec x) {
    MaxOf m;
    VectorXd row(x.size());
    for (Eigen::Index i = 1; i <= x.size(); ++i) {
      for (Eigen::Index j = 1; j <= x.size(); ++j) row(j - 1) = 1.0 / static_cast<double>(i + j - 1);
      const double v = row.dot(x);
      m.add(std::abs(v), sgn(v) * row);
    }
    return OracleResult::success(m.f, m.g);
  }));
  P.push_back(make("L1HILB", "TEST19 #24", VectorXd::Ones(50), 0.0, [](Vec x) {
    double f = 0;
    VectorXd g = VectorXd::Zero(x.size());
    VectorXd row(x.size());
    for (Eigen::Index i = 1; i <= x.size(); ++i) {
      for (Eigen::Index j = 1; j <= x.size(); ++j) row(j - 1) = 1.0 / static_cast<double>(i + j - 1);
      const double v = row.dot(x);
      f += std::abs(v);
      g += sgn(v) * row;
    }
    return OracleResult::success(f, g);
  }));
  Eigen::VectorXd x_shell = Eigen::VectorXd::Constant(15, 1e-4);
  x_shell(11) = 60.0;
  P.push_back(make("ShellDual", "TEST19 #25", x_shell, 32.348679, [](Vec x) {
    // The dual of Colville 1 (the Shell dual problem) with its constraints as exact penalties
    // (weight 100), data as Colville 1 (the Fortran's shared array).
    const ColvilleData& c = colville_data();
    const AdVector a = variables(x);
    const Eigen::Index n = 15;
    Ad cubic = constant(0.0, n);
    for (int j = 0; j < 5; ++j) cubic += c.d(j) * a(j) * a(j) * a(j);
    Ad f = ad_abs(2.0 * cubic);
    for (int j = 0; j < 5; ++j) {
      Ad cx = constant(0.0, n);
      for (int i = 0; i < 5; ++i) cx += c.C(i, j) * a(i);
      f += cx * a(j);
    }
    for (int j = 5; j < 15; ++j) f -= c.b(j - 5) * a(j);
    for (int j = 0; j < 5; ++j) {
      Ad t = -3.0 * c.d(j) * a(j) * a(j) - c.e(j);
      for (int i = 0; i < 5; ++i) t -= 2.0 * c.C(i, j) * a(i);
      for (int i = 5; i < 15; ++i) t += c.A(i - 5, j) * a(i);
      f += 100.0 * ad_max(constant(0.0, n), t);
    }
    for (int i = 0; i < 15; ++i) f += 100.0 * ad_max(constant(0.0, n), -a(i));
    return success(f);
  }));
  return P;
}


}  // namespace frictopt::optim
