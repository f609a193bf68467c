// SPDX-License-Identifier: MIT
// TEST22 of Lukšan & Vlček (TR V-798, 2000): the 15 linearly constrained minimax problems.
// Formulas follow the report; data, bounds, constraints and starting points follow the Fortran
// (EILD22, TAFU22), whose constraint normals are the columns of CG. Where pieces tie, the
// gradient of the first maximal one is returned (one Clarke subgradient).
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "testset/luksan_vlcek.hpp"
#include "luksan_vlcek_pieces.hpp"

namespace frictopt::optim {

namespace {

using Eigen::VectorXd;
using detail::Ad;
using detail::AdVector;
using detail::constant;
using detail::make;
using detail::make_minimax;
using detail::MaxOf;
using detail::Vec;
using detail::vec;

constexpr double kInf = std::numeric_limits<double>::infinity();

// EQUIL data (EILD22 label 100): y[0..39] demand weights, y[40..79] endowments, y[80..84]
// elasticities; 0-based as in the f2c translation.
std::vector<double> equil_data() {
  std::vector<double> y(85, 0.0);
  for (int i = 0; i < 40; ++i) {
    y[static_cast<std::size_t>(i)] = 1.0;
    y[static_cast<std::size_t>(i + 40)] = 0.1;
  }
  const std::pair<int, double> set[] = {
      {8, 2.}, {9, .8}, {11, .5}, {17, 1.2}, {18, .8}, {19, 1.2}, {20, 1.6}, {21, 2.}, {22, .6},
      {23, .1}, {24, 2.}, {25, .1}, {26, .6}, {27, 2.}, {31, 2.}, {32, 1.2}, {33, 1.2}, {34, .8},
      {36, 1.2}, {37, .1}, {38, 3.}, {39, 4.}, {40, 3.}, {41, 1.}, {44, 5.}, {47, 6.}, {49, 10.},
      {52, 5.}, {57, 9.}, {58, 10.}, {60, 4.}, {62, 7.}, {67, 10.}, {69, 3.}, {79, 11.}, {80, .5},
      {81, 1.2}, {82, .8}, {83, 2.}, {84, 1.5}};
  for (const auto& [i, v] : set) y[static_cast<std::size_t>(i)] = v;
  return y;
}

// Dembo 3 data (EILD22 label 130), 0-based.
const double* dembo3_data() {
  static const double y[44] = {1.715, .035, 4.0565, 10., 3e3, -.063, .0059553571, .88392857,
                               -.1175625, 1.1088, .1303533, -.0066033, 6.6173269e-4, .017239878,
                               -.0056595559, -.019120592, 56.85075, 1.08702, .32175, -.03762,
                               .006198, 2462.3121, -25.125634, 161.18996, 5e3, -489510., 44.333333,
                               .33, .022556, -.007595, 6.1e-4, -5e-4, .819672, .819672, 24500.,
                               -250., .010204082, 1.2244898e-5, 6.25e-5, 6.25e-5, -7.625e-5, 1.22,
                               1., -1.};
  return y;
}

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
    p.constraints.lower = vec({-kInf, 0.01});
    p.constraints.A_in = Eigen::MatrixXd{{-0.05, 1.0}};  // 0.05 x1 − x2 >= −0.5
    p.constraints.b_in = vec({0.5});
    P.push_back(p);
  }
  {
    auto p = make("MAD5", "TEST22 #4", vec({-1, 3}), -0.42928061, mad45);
    p.constraints.lower = vec({-kInf, 0.01});
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
    // MAD6: max_k |f_k|, f_k = (1 + 2 Σ_j cos(y_k x_j))/15, y_k = 2π sin((8.5 + k/2)°), k = 1..163;
    // x_{j+1} − x_j ≥ 0.4, x_6 − x_4 = 1, x_1 ≥ 0.4. The Fortran marks x_7 fixed (IX = 5)
    // without setting its bounds (testsets pitfall); we fix it at its starting value 3.5.
    VectorXd x0(7);
    for (int i = 1; i <= 7; ++i) x0(i - 1) = 0.5 * i;
    auto p = make_minimax("MAD6", "TEST22 #6", x0, 0.10183089, [](Vec x, bool pieces) {
      return detail::minimax(x, 163, true, pieces, [](const AdVector& a, int k) {
        const double y = 2.0 * std::numbers::pi * std::sin((0.5 * k + 8.5) * std::numbers::pi / 180.0);
        Ad s = constant(0.0, a.size());
        for (Eigen::Index j = 0; j < a.size(); ++j) s += cos(y * a(j));
        return Ad((2.0 * s + 1.0) / 15.0);
      });
    });
    p.constraints.lower = VectorXd::Constant(7, -kInf);
    p.constraints.upper = VectorXd::Constant(7, kInf);
    p.constraints.lower(0) = 0.4;
    p.constraints.lower(6) = 3.5;
    p.constraints.upper(6) = 3.5;
    p.constraints.A_in = Eigen::MatrixXd::Zero(6, 7);
    for (int i = 0; i < 6; ++i) {  // x_{i+1} − x_{i+2} ≤ −0.4
      p.constraints.A_in(i, i) = 1.0;
      p.constraints.A_in(i, i + 1) = -1.0;
    }
    p.constraints.b_in = VectorXd::Constant(6, -0.4);
    p.constraints.A_eq = Eigen::MatrixXd::Zero(1, 7);
    p.constraints.A_eq(0, 3) = -1.0;
    p.constraints.A_eq(0, 5) = 1.0;
    p.constraints.b_eq = vec({1.0});
    P.push_back(p);
  }
  {
    // EQUIL: an economic equilibrium (8 goods, 5 agents), max_k f_k with f_k the excess demand
    // of good k; Σx = 1, x ≥ 1e-8. Data Y of the Fortran (EILD22 label 100).
    auto p = make_minimax("EQUIL", "TEST22 #7", VectorXd::Constant(8, 0.125), 0.0, [](Vec x, bool pieces) {
      static const std::vector<double> y = equil_data();
      return detail::minimax(x, 8, false, pieces, [](const AdVector& a, int ka) {
        const Eigen::Index n = 8;
        Ad f = constant(0.0, n);
        for (int i = 1; i <= 5; ++i) {
          const int k = (i - 1) * 8;
          const double e = y[static_cast<std::size_t>(i + 79)];
          Ad s = constant(0.0, n);
          Ad q = constant(0.0, n);
          for (int j = 1; j <= 8; ++j) {
            s += y[static_cast<std::size_t>(k + j - 1)] * pow(a(j - 1), 1.0 - e);
            q += y[static_cast<std::size_t>(k + j + 39)] * a(j - 1);
          }
          f += y[static_cast<std::size_t>(k + ka - 1)] * q / (pow(a(ka - 1), e) * s) -
               y[static_cast<std::size_t>(k + ka + 39)];
        }
        return f;
      });
    });
    p.constraints.lower = VectorXd::Constant(8, 1e-8);
    p.constraints.A_eq = Eigen::MatrixXd::Ones(1, 8);
    p.constraints.b_eq = vec({1.0});
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
  {
    // MAD8: max_k |f_k|, f_k = −1 + Σx + x_i(x_i − 1) (k even, i = (k+2)/2) or x_i(2x_i − 1)
    // (k odd, i = (k+1)/2), k = 1..38; bounds x_1..x_10 ≥ 0.5.
    auto p = make_minimax("MAD8", "TEST22 #10", VectorXd::Constant(20, 100.0), 0.50694799, [](Vec x, bool pieces) {
      return detail::minimax(x, 38, true, pieces, [](const AdVector& a, int ka) {
        Ad f = constant(-1.0, a.size());
        for (Eigen::Index i = 0; i < a.size(); ++i) f += a(i);
        if (ka % 2 == 0) {
          const int i = (ka + 2) / 2 - 1;
          f += a(i) * (a(i) - 1.0);
        } else {
          const int i = (ka + 1) / 2 - 1;
          f += a(i) * (2.0 * a(i) - 1.0);
        }
        return f;
      });
    });
    p.constraints.lower = VectorXd::Constant(20, -kInf);
    p.constraints.lower.head(10).setConstant(0.5);
    P.push_back(p);
  }
  {
    // BPfilter: band-pass filter design, max_k |f_k| over 124 frequencies; x_1..x_8 ≥ 0 and
    // 1e4·x_i − x_{i+4} ≥ 0 (i = 1..4).
    const VectorXd x0 = vec({0.0398, 9.68e-5, 1.03e-4, 0.0389, 1.01, 0.968, 1.03, 0.988, -11.6});
    auto p = make_minimax("BPfilter", "TEST22 #11", x0, 0.27607734e-3, [](Vec x, bool pieces) {
      static const std::vector<double> y = [] {
        std::vector<double> v(124);
        const int l = (124 - 2) / 2;
        const double a = 0.025154 / (l - 1);
        v[0] = 0.96732;
        for (int i = 2; i <= l + 1; ++i) {
          v[static_cast<std::size_t>(i - 1)] = (i - 2) * a + 0.987423;
          v[static_cast<std::size_t>(i + l - 1)] = v[static_cast<std::size_t>(i - 1)];
        }
        v[123] = 1.03268;
        return v;
      }();
      return detail::minimax(x, 124, true, pieces, [](const AdVector& a, int ka) {
        double w = y[static_cast<std::size_t>(ka - 1)];
        const double s = (ka > 62 && ka < 124) ? -1.0 : 1.0;
        Ad sum = constant(-8.0 * std::log(w), a.size());
        w *= w;
        for (int i = 0; i < 4; ++i) {
          const Ad b = a(i + 4) * a(i + 4) - w;
          sum += log(b * b + w * a(i) * a(i));
        }
        Ad f = (0.5 * sum - a(8)) * s;
        if (ka == 1 || ka == 124) f += 3.0164;
        return f;
      });
    });
    p.constraints.lower = VectorXd::Constant(9, -kInf);
    p.constraints.lower.head(8).setZero();
    p.constraints.A_in = Eigen::MatrixXd::Zero(4, 9);
    for (int i = 0; i < 4; ++i) {  // −1e4 x_i + x_{i+4} ≤ 0
      p.constraints.A_in(i, i) = -1e4;
      p.constraints.A_in(i, i + 4) = 1.0;
    }
    p.constraints.b_in = VectorXd::Zero(4);
    P.push_back(p);
  }
  {
    // HS114 (alkylation process) as a minimax of the cost and the cost ± 500 × the equality
    // residuals; bounds and 5 linear constraints of the Fortran (whose x_10 bounds are 140, 160;
    // the report prints 145, 162). The standard start violates the constraints (pitfall).
    const VectorXd x0 = vec({1745, 12000, 110, 3048, 1974, 89.2, 92.8, 8, 3.6, 145});
    auto p = make_minimax("HS114", "TEST22 #12", x0, -1768.8070, [](Vec x, bool pieces) {
      return detail::minimax(x, 9, false, pieces, [](const AdVector& a, int ka) {
        const double pen = 500.0;
        const double q = 0.99;
        Ad f = 5.04 * a(0) + 0.035 * a(1) + 10.0 * a(2) + 3.36 * a(4) - 0.063 * a(3) * a(6);
        const Ad r1 = 1.12 * a(0) + a(0) * a(7) * (0.13167 - 0.00667 * a(7));
        const Ad r2 = 1.098 * a(7) - 0.038 * a(7) * a(7) + 57.425 + 0.325 * a(5);
        const Ad r3 = 98000.0 * a(2) / (a(3) * a(8) + 1000.0 * a(2)) - a(5);
        const Ad r4 = (a(1) + a(4)) / a(0) - a(7);
        switch (ka) {
          case 2: return Ad(f + pen * (r1 - a(3) / q));
          case 3: return Ad(f - pen * (r1 - a(3) * q));
          case 4: return Ad(f + pen * (r2 - a(6) / q));
          case 5: return Ad(f - pen * (r2 - a(6) * q));
          case 6: return Ad(f + pen * r3);
          case 7: return Ad(f - pen * r3);
          case 8: return Ad(f + pen * r4);
          case 9: return Ad(f - pen * r4);
          default: return f;
        }
      });
    });
    p.constraints.lower = vec({1e-5, 1e-5, 1e-5, 1e-5, 1e-5, 85, 90, 3, 1.2, 140});
    p.constraints.upper = vec({2000, 16000, 120, 5000, 2000, 93, 95, 12, 4, 160});
    p.constraints.A_in = Eigen::MatrixXd::Zero(4, 10);
    p.constraints.A_in(0, 8) = 0.9;          // 0.9 x9 + 0.222 x10 ≤ 35.82
    p.constraints.A_in(0, 9) = 0.222;
    p.constraints.A_in(1, 8) = -1.0 / 0.9;   // x9/0.9 + 0.222 x10 ≥ 35.82
    p.constraints.A_in(1, 9) = -0.222;
    p.constraints.A_in(2, 6) = -3.0;         // 3 x7 − 0.99 x10 ≥ 133
    p.constraints.A_in(2, 9) = 0.99;
    p.constraints.A_in(3, 6) = 3.0;          // 3 x7 − x10/0.99 ≤ 133
    p.constraints.A_in(3, 9) = -1.0 / 0.99;
    p.constraints.b_in = vec({35.82, -35.82, -133, 133});
    p.constraints.A_eq = Eigen::MatrixXd::Zero(1, 10);  // −x1 + 1.22 x4 − x5 = 0
    p.constraints.A_eq(0, 0) = -1.0;
    p.constraints.A_eq(0, 3) = 1.22;
    p.constraints.A_eq(0, 4) = -1.0;
    p.constraints.b_eq = vec({0.0});
    P.push_back(p);
  }
  {
    // Dembo 3 (a geometric-programming problem, Dembo 1976) as max of the cost and the cost +
    // 1e5 × each constraint g_k − 1; two linear constraints and bounds of the Fortran.
    const VectorXd x0 = vec({1745, 110, 3048, 89, 92, 8, 145});
    auto p = make_minimax("Dembo3", "TEST22 #13", x0, 1227.2260, [](Vec x, bool pieces) {
      return detail::minimax(x, 13, false, pieces, [](const AdVector& a, int ka) {
        const double* y = dembo3_data();
        const double pen = 1e5;
        Ad f = y[0] * a(0) + y[1] * a(0) * a(5) + y[2] * a(2) + y[3] * a(1) + y[4] + y[5] * a(2) * a(4);
        switch (ka) {
          case 2: return Ad(f + pen * (y[6] * a(5) * a(5) + y[7] * a(2) / a(0) + y[8] * a(5) - 1.0));
          case 3: return Ad(f + pen * ((y[9] + y[10] * a(5) + y[11] * a(5) * a(5)) * a(0) / a(2) - 1.0));
          case 4: return Ad(f + pen * (y[12] * a(5) * a(5) + y[13] * a(4) + y[14] * a(3) + y[15] * a(5) - 1.0));
          case 5: return Ad(f + pen * ((y[16] + y[17] * a(5) + y[18] * a(3) + y[19] * a(5) * a(5)) / a(4) - 1.0));
          case 6: return Ad(f + pen * (y[20] * a(6) + (y[21] / a(3) + y[22]) * a(1) / a(2) - 1.0));
          case 7: return Ad(f + pen * ((y[23] + (y[24] + y[25] / a(3)) * a(1) / a(2)) / a(6) - 1.0));
          case 8: return Ad(f + pen * ((y[26] + y[27] * a(6)) / a(4) - 1.0));
          case 9: return Ad(f + pen * ((y[32] * a(0) + y[33]) / a(2) - 1.0));
          case 10: return Ad(f + pen * ((y[34] / a(3) + y[35]) * a(1) / a(2) - 1.0));
          case 11: return Ad(f + pen * ((y[36] + y[37] * a(2) / a(1)) * a(3) - 1.0));
          case 12: return Ad(f + pen * (y[38] * a(0) * a(5) + y[39] * a(0) + y[40] * a(2) - 1.0));
          case 13: return Ad(f + pen * ((y[41] * a(2) + y[42]) / a(0) + y[43] * a(5) - 1.0));
          default: return f;
        }
      });
    });
    p.constraints.lower = vec({1, 1, 1, 85, 90, 3, 145});
    p.constraints.upper = vec({2000, 120, 5000, 93, 95, 12, 162});
    const double* y = dembo3_data();
    p.constraints.A_in = Eigen::MatrixXd::Zero(2, 7);
    p.constraints.A_in(0, 4) = y[28];
    p.constraints.A_in(0, 6) = y[29];
    p.constraints.A_in(1, 0) = y[31];
    p.constraints.A_in(1, 2) = y[30];
    p.constraints.b_in = vec({1.0, 1.0});
    P.push_back(p);
  }
  {
    // Dembo 5 (heat exchanger design) as a minimax with penalty 1e5; three linear constraints.
    const VectorXd x0 = vec({5000, 5000, 5000, 200, 350, 150, 225, 425});
    auto p = make_minimax("Dembo5", "TEST22 #14", x0, 7049.2480, [](Vec x, bool pieces) {
      return detail::minimax(x, 4, false, pieces, [](const AdVector& a, int ka) {
        const double pen = 1e5;
        Ad f = a(0) + a(1) + a(2);
        switch (ka) {
          case 2: return Ad(f + pen * ((833.33252 * a(3) / a(0) + 100.0 - 83333.333 / a(0)) / a(5) - 1.0));
          case 3: return Ad(f + pen * ((1250.0 * (a(4) - a(3)) / a(1) + a(3)) / a(6) - 1.0));
          case 4: return Ad(f + pen * (((1.25e6 - 2500.0 * a(4)) / a(2) + a(4)) / a(7) - 1.0));
          default: return f;
        }
      });
    });
    p.constraints.lower = vec({100, 1000, 1000, 10, 10, 10, 10, 10});
    p.constraints.upper = vec({1e4, 1e4, 1e4, 1000, 1000, 1000, 1000, 1000});
    p.constraints.A_in = Eigen::MatrixXd::Zero(3, 8);
    p.constraints.A_in(0, 3) = 0.0025;   // 0.0025 (x4 + x6) ≤ 1
    p.constraints.A_in(0, 5) = 0.0025;
    p.constraints.A_in(1, 3) = -0.0025;  // 0.0025 (−x4 + x5 + x7) ≤ 1
    p.constraints.A_in(1, 4) = 0.0025;
    p.constraints.A_in(1, 6) = 0.0025;
    p.constraints.A_in(2, 4) = -0.01;    // 0.01 (−x5 + x8) ≤ 1
    p.constraints.A_in(2, 7) = 0.01;
    p.constraints.b_in = vec({1.0, 1.0, 1.0});
    P.push_back(p);
  }
  {
    // Dembo 7 (a membrane separation process) as a minimax with penalty 1e3; one linear
    // constraint 0.002 (x11 − x12) ≤ 1 and bounds.
    const VectorXd x0 = vec({0.8, 0.83, 0.85, 0.87, 0.9, 0.1, 0.12, 0.19, 0.25, 0.29, 512, 13.1, 71.8, 640, 650, 5.7});
    auto p = make_minimax("Dembo7", "TEST22 #15", x0, 174.78699, [](Vec x, bool pieces) {
      return detail::minimax(x, 19, false, pieces, [](const AdVector& a, int ka) {
        const double pen = 1e3;
        // 1-based names as in the Fortran.
        auto X = [&](int i) -> const Ad& { return a(i - 1); };
        Ad f = 1.262626 * (X(12) + X(13) + X(14) + X(15) + X(16)) -
               1.23106 * (X(1) * X(12) + X(2) * X(13) + X(3) * X(14) + X(4) * X(15) + X(5) * X(16));
        switch (ka) {
          case 2: return Ad(f + pen * (X(1) * ((0.03475 - 0.00975 * X(1)) / X(6) + 0.975) - 1.0));
          case 3: return Ad(f + pen * (X(2) * ((0.03475 - 0.00975 * X(2)) / X(7) + 0.975) - 1.0));
          case 4: return Ad(f + pen * (X(3) * ((0.03475 - 0.00975 * X(3)) / X(8) + 0.975) - 1.0));
          case 5: return Ad(f + pen * (X(4) * ((0.03475 - 0.00975 * X(4)) / X(9) + 0.975) - 1.0));
          case 6: return Ad(f + pen * (X(5) * ((0.03475 - 0.00975 * X(5)) / X(10) + 0.975) - 1.0));
          case 7: return Ad(f + pen * ((X(6) + (X(1) - X(6)) * X(12) / X(11)) / X(7) - 1.0));
          case 8: return Ad(f + pen * ((X(7) + 0.002 * (X(7) - X(1)) * X(12)) / X(8) + 0.002 * X(13) * (X(2) / X(8) - 1.0) - 1.0));
          case 9: return Ad(f + pen * (X(8) + X(9) + 0.002 * X(13) * (X(8) - X(2)) + 0.002 * X(14) * (X(3) - X(9)) - 1.0));
          case 10: return Ad(f + pen * ((X(9) + ((X(4) - X(8)) * X(15) + 500.0 * (X(10) - X(9))) / X(14)) / X(3) - 1.0));
          case 11: return Ad(f + pen * (X(10) / X(4) + (X(5) / X(4) - 1.0) * X(16) / X(15) + 500.0 * (1.0 - X(10) / X(4)) / X(15) - 1.0));
          case 12: return Ad(f + pen * (0.9 / X(4) + 0.002 * X(16) * (1.0 - X(5) / X(4)) - 1.0));
          case 13: return Ad(f + pen * (X(12) / X(11) - 1.0));
          case 14: return Ad(f + pen * (X(4) / X(5) - 1.0));
          case 15: return Ad(f + pen * (X(3) / X(4) - 1.0));
          case 16: return Ad(f + pen * (X(2) / X(3) - 1.0));
          case 17: return Ad(f + pen * (X(1) / X(2) - 1.0));
          case 18: return Ad(f + pen * (X(9) / X(10) - 1.0));
          case 19: return Ad(f + pen * X(8) / X(9) - pen);
          default: return f;
        }
      });
    });
    p.constraints.lower = vec({0.1, 0.1, 0.1, 0.1, 0.9, 1e-4, 0.1, 0.1, 0.1, 0.1, 1, 1e-6, 1, 500, 500, 1e-6});
    p.constraints.upper = vec({0.9, 0.9, 0.9, 0.9, 1.0, 0.1, 0.9, 0.9, 0.9, 0.9, 1e4, 5e3, 5e3, 1e4, 1e4, 5e3});
    p.constraints.A_in = Eigen::MatrixXd::Zero(1, 16);
    p.constraints.A_in(0, 10) = 0.002;
    p.constraints.A_in(0, 11) = -0.002;
    p.constraints.b_in = vec({1.0});
    P.push_back(p);
  }
  return P;
}


}  // namespace frictopt::optim
