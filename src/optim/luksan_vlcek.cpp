// SPDX-License-Identifier: MIT
// Formulas follow the report; data and starting points follow the Fortran files (TEST19,
// TEST22), which the report's tables were computed with. Where several pieces of a max tie, the
// gradient of the first one in the order listed is returned (one Clarke subgradient).
#include "frictopt/optim/luksan_vlcek.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "frictopt/core/error.hpp"

namespace frictopt::optim {

namespace {

using Eigen::VectorXd;
using Vec = const Eigen::Ref<const Eigen::VectorXd>&;

// Running maximum of smooth pieces with their gradients.
struct MaxOf {
  double f = -std::numeric_limits<double>::infinity();
  VectorXd g;
  void add(double value, const VectorXd& grad) {
    if (value > f) {
      f = value;
      g = grad;
    }
  }
};

double sgn(double t) { return t >= 0.0 ? 1.0 : -1.0; }

VectorXd vec(std::initializer_list<double> v) {
  VectorXd x(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double a : v) x(i++) = a;
  return x;
}

LuksanVlcekProblem make(std::string name, std::string source, VectorXd x0, double f_star,
                        FunctionOracle::Function f) {
  LuksanVlcekProblem p;
  p.name = std::move(name);
  p.source = std::move(source);
  p.x0 = std::move(x0);
  p.f_star = f_star;
  p.evaluate = std::move(f);
  return p;
}

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

// Wong 2 / Wong 3 (TEST22 #8, #9): the common base and pieces 2–6.
void wong_common(Vec x, double& base, VectorXd& gb) {
  const Eigen::Index n = x.size();
  gb = VectorXd::Zero(n);
  base = x(0) * x(0) + x(1) * x(1) + x(0) * x(1) - 14 * x(0) - 16 * x(1) + std::pow(x(2) - 10, 2) +
         4 * std::pow(x(3) - 5, 2) + std::pow(x(4) - 3, 2) + 2 * std::pow(x(5) - 1, 2) +
         5 * x(6) * x(6) + 7 * std::pow(x(7) - 11, 2) + 2 * std::pow(x(8) - 10, 2) +
         std::pow(x(9) - 7, 2);
  gb(0) = 2 * x(0) + x(1) - 14;
  gb(1) = 2 * x(1) + x(0) - 16;
  gb(2) = 2 * (x(2) - 10);
  gb(3) = 8 * (x(3) - 5);
  gb(4) = 2 * (x(4) - 3);
  gb(5) = 4 * (x(5) - 1);
  gb(6) = 10 * x(6);
  gb(7) = 14 * (x(7) - 11);
  gb(8) = 4 * (x(8) - 10);
  gb(9) = 2 * (x(9) - 7);
}

void wong_pieces_2_to_6(Vec x, double base, const VectorXd& gb, MaxOf& m) {
  const Eigen::Index n = x.size();
  VectorXd g(n);
  g = gb;
  g(0) += 60 * (x(0) - 2); g(1) += 80 * (x(1) - 3); g(2) += 40 * x(2); g(3) += -70;
  m.add(base + 10 * (3 * std::pow(x(0) - 2, 2) + 4 * std::pow(x(1) - 3, 2) + 2 * x(2) * x(2) - 7 * x(3) - 120), g);
  g = gb;
  g(0) += 100 * x(0); g(1) += 80; g(2) += 20 * (x(2) - 6); g(3) += -20;
  m.add(base + 10 * (5 * x(0) * x(0) + 8 * x(1) + std::pow(x(2) - 6, 2) - 2 * x(3) - 40), g);
  g = gb;
  g(0) += 10 * (x(0) - 8); g(1) += 40 * (x(1) - 4); g(4) += 60 * x(4); g(5) += -10;
  m.add(base + 10 * (0.5 * std::pow(x(0) - 8, 2) + 2 * std::pow(x(1) - 4, 2) + 3 * x(4) * x(4) - x(5) - 30), g);
  g = gb;
  g(0) += 20 * x(0) - 20 * x(1); g(1) += 40 * (x(1) - 2) - 20 * x(0); g(4) += 140; g(5) += -60;
  m.add(base + 10 * (x(0) * x(0) + 2 * std::pow(x(1) - 2, 2) - 2 * x(0) * x(1) + 14 * x(4) - 6 * x(5)), g);
  g = gb;
  g(0) += -30; g(1) += 60; g(8) += 240 * (x(8) - 8); g(9) += -70;
  m.add(base + 10 * (6 * x(1) - 3 * x(0) + 12 * std::pow(x(8) - 8, 2) - 7 * x(9)), g);
}

}  // namespace

bool LuksanVlcekProblem::solved(double f, double tolerance) const {
  return std::abs(f - f_star) <= tolerance * std::max(1.0, std::abs(f_star));
}

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
  return P;
}

std::vector<LuksanVlcekProblem> luksan_vlcek_constrained() {
  std::vector<LuksanVlcekProblem> P;
  auto mad12 = [](Vec x) {
    MaxOf m;
    m.add(x(0) * x(0) + x(1) * x(1) + x(0) * x(1) - 1, vec({2 * x(0) + x(1), 2 * x(1) + x(0)}));
    m.add(std::sin(x(0)), vec({std::cos(x(0)), 0}));
    m.add(-std::cos(x(1)), vec({0, std::sin(x(1))}));
    return OracleResult::success(m.f, m.g);
  };
  auto mad45 = [](Vec x) {
    if (!(x(1) > 0)) return OracleResult::failure("log(x2) undefined for x2 <= 0");
    MaxOf m;
    const double e = std::exp(x(0) - x(1));
    m.add(-e, vec({-e, e}));
    m.add(std::sinh(x(0) - 1) - 1, vec({std::cosh(x(0) - 1), 0}));
    m.add(-std::log(x(1)) - 1, vec({0, -1 / x(1)}));
    return OracleResult::success(m.f, m.g);
  };
  {
    auto p = make("MAD1", "TEST22 #1", vec({1, 2}), -0.38965952, mad12);
    p.constraints.A_in = Eigen::MatrixXd{{-1.0, -1.0}};  // x1 + x2 >= 0.5
    p.constraints.b_in = vec({-0.5});
    P.push_back(p);
  }
  {
    auto p = make("MAD2", "TEST22 #2", vec({-2, -1}), -0.33035714, mad12);
    p.constraints.A_in = Eigen::MatrixXd{{3.0, 1.0}};  // 3 x1 + x2 <= -2.5
    p.constraints.b_in = vec({-2.5});
    P.push_back(p);
  }
  {
    auto p = make("MAD4", "TEST22 #3", vec({-1, 0.01}), -0.44891079, mad45);
    p.constraints.lower = vec({-std::numeric_limits<double>::infinity(), 0.01});
    p.constraints.A_in = Eigen::MatrixXd{{-0.05, 1.0}};  // 0.05 x1 − x2 >= −0.5
    p.constraints.b_in = vec({0.5});
    P.push_back(p);
  }
  {
    auto p = make("MAD5", "TEST22 #4", vec({-1, 3}), -0.42928061, mad45);
    p.constraints.lower = vec({-std::numeric_limits<double>::infinity(), 0.01});
    p.constraints.A_in = Eigen::MatrixXd{{0.9, -1.0}};  // −0.9 x1 + x2 >= 1
    p.constraints.b_in = vec({-1.0});
    P.push_back(p);
  }
  {
    // Three points in the regular pentagon {p : ⟨(sin φ_j, cos φ_j), p⟩ ≤ 1}, φ_j = 2πj/5;
    // maximize the smallest pairwise distance. The standard start violates the constraints.
    auto p = make("Pentagon", "TEST22 #5", vec({-1, 0, 0, -1, 1, 1}), -1.85961870, [](Vec x) {
      MaxOf m;
      for (int i = 0; i < 3; ++i) {
        const int a = 2 * i;
        const int b = 2 * ((i + 1) % 3);
        const double dx = x(a) - x(b);
        const double dy = x(a + 1) - x(b + 1);
        const double r = std::hypot(dx, dy);
        VectorXd g = VectorXd::Zero(6);
        if (r > 0) {
          g(a) = -dx / r;
          g(a + 1) = -dy / r;
          g(b) = dx / r;
          g(b + 1) = dy / r;
        }
        m.add(-r, g);
      }
      return OracleResult::success(m.f, m.g);
    });
    p.constraints.A_in = Eigen::MatrixXd::Zero(15, 6);
    p.constraints.b_in = VectorXd::Ones(15);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 5; ++j) {
        const double phi = 2 * std::numbers::pi * j / 5;
        p.constraints.A_in(5 * i + j, 2 * i) = std::sin(phi);
        p.constraints.A_in(5 * i + j, 2 * i + 1) = std::cos(phi);
      }
    P.push_back(p);
  }
  {
    auto p = make("Wong2", "TEST22 #8", vec({2, 3, 5, 5, 1, 2, 7, 3, 6, 10}), 24.306209, [](Vec x) {
      double base = 0;
      VectorXd gb;
      wong_common(x, base, gb);
      base += 45;
      MaxOf m;
      m.add(base, gb);
      wong_pieces_2_to_6(x, base, gb, m);
      return OracleResult::success(m.f, m.g);
    });
    p.constraints.A_in = Eigen::MatrixXd::Zero(3, 10);
    p.constraints.A_in.row(0) << 4, 5, 0, 0, 0, 0, -3, 9, 0, 0;
    p.constraints.A_in.row(1) << 10, -8, 0, 0, 0, 0, -17, 2, 0, 0;
    p.constraints.A_in.row(2) << -8, 2, 0, 0, 0, 0, 0, 0, 5, -2;
    p.constraints.b_in = vec({105, 0, 12});
    P.push_back(p);
  }
  {
    auto p = make("Wong3", "TEST22 #9",
                  vec({2, 3, 5, 5, 1, 2, 7, 3, 6, 10, 2, 2, 6, 15, 1, 2, 1, 2, 1, 3}), 133.72828,
                  [](Vec x) {
      double base = 0;
      VectorXd gb10;
      wong_common(x, base, gb10);
      VectorXd gb = VectorXd::Zero(20);
      gb.head(10) = gb10.head(10);
      base += std::pow(x(10) - 9, 2) + 10 * std::pow(x(11) - 1, 2) + 5 * std::pow(x(12) - 7, 2) +
              4 * std::pow(x(13) - 14, 2) + 27 * std::pow(x(14) - 1, 2) + std::pow(x(15), 4) +
              std::pow(x(16) - 2, 2) + 13 * std::pow(x(17) - 2, 2) + std::pow(x(18) - 3, 2) +
              x(19) * x(19) + 95;
      gb(10) = 2 * (x(10) - 9);
      gb(11) = 20 * (x(11) - 1);
      gb(12) = 10 * (x(12) - 7);
      gb(13) = 8 * (x(13) - 14);
      gb(14) = 54 * (x(14) - 1);
      gb(15) = 4 * std::pow(x(15), 3);
      gb(16) = 2 * (x(16) - 2);
      gb(17) = 26 * (x(17) - 2);
      gb(18) = 2 * (x(18) - 3);
      gb(19) = 2 * x(19);
      MaxOf m;
      m.add(base, gb);
      wong_pieces_2_to_6(x, base, gb, m);
      VectorXd g;
      g = gb; g(0) += 20 * x(0); g(10) += 150; g(11) += -80;
      m.add(base + 10 * (x(0) * x(0) + 15 * x(10) - 8 * x(11) - 28), g);
      g = gb; g(0) += 40; g(1) += 90; g(12) += 100 * x(12); g(13) += -90;
      m.add(base + 10 * (4 * x(0) + 9 * x(1) + 5 * x(12) * x(12) - 9 * x(13) - 87), g);
      g = gb; g(0) += 30; g(1) += 40; g(12) += 60 * (x(12) - 6); g(13) += -140;
      m.add(base + 10 * (3 * x(0) + 4 * x(1) + 3 * std::pow(x(12) - 6, 2) - 14 * x(13) - 10), g);
      g = gb; g(0) += 280 * x(0); g(14) += 350; g(15) += -790;
      m.add(base + 10 * (14 * x(0) * x(0) + 35 * x(14) - 79 * x(15) - 92), g);
      g = gb; g(1) += 300 * x(1); g(14) += 110; g(15) += -610;
      m.add(base + 10 * (15 * x(1) * x(1) + 11 * x(14) - 61 * x(15) - 54), g);
      g = gb; g(0) += 100 * x(0); g(1) += 20; g(16) += 360 * std::pow(x(16), 3); g(17) += -10;
      m.add(base + 10 * (5 * x(0) * x(0) + 2 * x(1) + 9 * std::pow(x(16), 4) - x(17) - 68), g);
      g = gb; g(0) += 20 * x(0); g(1) += -10; g(18) += 190; g(19) += -200;
      m.add(base + 10 * (x(0) * x(0) - x(1) + 19 * x(18) - 20 * x(19) + 19), g);
      g = gb; g(0) += 140 * x(0); g(1) += 100 * x(1); g(18) += 20 * x(18); g(19) += -300;
      m.add(base + 10 * (7 * x(0) * x(0) + 5 * x(1) * x(1) + x(18) * x(18) - 30 * x(19)), g);
      return OracleResult::success(m.f, m.g);
    });
    p.constraints.A_in = Eigen::MatrixXd::Zero(4, 20);
    p.constraints.A_in.row(0).head(10) << 4, 5, 0, 0, 0, 0, -3, 9, 0, 0;
    p.constraints.A_in.row(1).head(10) << 10, -8, 0, 0, 0, 0, -17, 2, 0, 0;
    p.constraints.A_in.row(2).head(10) << -8, 2, 0, 0, 0, 0, 0, 0, 5, -2;
    p.constraints.A_in(3, 0) = 1;
    p.constraints.A_in(3, 1) = 1;
    p.constraints.A_in(3, 10) = 4;
    p.constraints.A_in(3, 11) = -21;
    p.constraints.b_in = vec({105, 0, 12, 0});
    P.push_back(p);
  }
  return P;
}

LuksanVlcekProblem luksan_vlcek_problem(std::string_view name) {
  std::string names;
  for (auto set : {luksan_vlcek_unconstrained(), luksan_vlcek_constrained()}) {
    for (auto& p : set) {
      if (p.name == name) return p;
      names += (names.empty() ? "" : ", ") + p.name;
    }
  }
  throw InvalidInput("luksan_vlcek_problem: unknown name '" + std::string(name) + "'; expected one of " + names);
}

}  // namespace frictopt::optim
