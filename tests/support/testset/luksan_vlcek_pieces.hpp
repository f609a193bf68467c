// SPDX-License-Identifier: MIT
// Building blocks shared by the two Lukšan–Vlček problem files (TEST19, TEST22): a running
// maximum of smooth pieces, a vector literal, and forward-mode differentiation of the smooth
// pieces with Eigen's AutoDiffScalar, so that each piece is written once and its gradient
// cannot disagree with it (the tests still compare with finite differences).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <limits>
#include <string>
#include <unsupported/Eigen/AutoDiff>
#include <utility>
#include <vector>

#include "testset/luksan_vlcek.hpp"

namespace frictopt::optim::detail {

using Vec = const Eigen::Ref<const Eigen::VectorXd>&;
/// A scalar carrying its gradient with respect to all n variables.
using Ad = Eigen::AutoDiffScalar<Eigen::VectorXd>;
using AdVector = Eigen::Matrix<Ad, Eigen::Dynamic, 1>;

/// Running maximum of smooth pieces with their gradients; at ties the first piece wins.
struct MaxOf {
  double f = -std::numeric_limits<double>::infinity();
  Eigen::VectorXd g;
  int index = -1;  ///< 0-based position, among the pieces added, of the one that is the max
  int added = 0;
  void add(double value, const Eigen::VectorXd& grad) {
    if (value > f) {
      f = value;
      g = grad;
      index = added;
    }
    ++added;
  }
  void add(const Ad& piece) { add(piece.value(), piece.derivatives()); }
};

inline double sgn(double t) { return t >= 0.0 ? 1.0 : -1.0; }

inline Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd x(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double a : v) x(i++) = a;
  return x;
}

/// x as AutoDiff variables: x_i with derivative e_i.
inline AdVector variables(Vec x) {
  AdVector a(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) a(i) = Ad(x(i), x.size(), i);
  return a;
}

/// A constant (zero derivative) in n variables.
inline Ad constant(double c, Eigen::Index n) { return Ad(c, Eigen::VectorXd::Zero(n)); }

/// max(a, b) and |a| for AutoDiff: the derivative of the branch taken (one Clarke subgradient).
inline Ad ad_max(const Ad& a, const Ad& b) { return b.value() > a.value() ? b : a; }
inline Ad ad_abs(const Ad& a) { return a.value() >= 0.0 ? a : Ad(-a); }
/// sqrt(a² + b²) with the subgradient 0 at the origin (where the norm has no gradient).
inline Ad ad_hypot(const Ad& a, const Ad& b) {
  const double r = std::hypot(a.value(), b.value());
  if (r == 0.0) return constant(0.0, a.derivatives().size());
  return Ad(r, (a.value() * a.derivatives() + b.value() * b.derivatives()) / r);
}

inline OracleResult success(const Ad& f) { return OracleResult::success(f.value(), f.derivatives()); }

inline LuksanVlcekProblem make(std::string name, std::string source, Eigen::VectorXd x0, double f_star,
                               FunctionOracle::Function f) {
  LuksanVlcekProblem p;
  p.name = std::move(name);
  p.source = std::move(source);
  p.x0 = std::move(x0);
  p.f_star = f_star;
  p.evaluate = std::move(f);
  return p;
}

/// Minimax objective max_k f_k(x) (or max_k |f_k(x)| when `absolute`), pieces k = 1..m from
/// `piece(x, k)` (the Fortran's TAFU22 numbering), one subgradient = gradient of the first
/// maximal piece (times its sign). With `with_pieces`, the answer also carries the cut of every
/// other piece (f_k or |f_k|, OracleResult::pieces): the structured oracle of
/// LuksanVlcekProblem::evaluate_with_pieces.
template <class Piece>
OracleResult minimax(Vec x, int m, bool absolute, bool with_pieces, const Piece& piece) {
  const AdVector a = variables(x);
  MaxOf best;
  std::vector<PieceCut> cuts;  // every piece's, only for the structured oracle
  if (with_pieces) cuts.reserve(static_cast<std::size_t>(m));
  for (int k = 1; k <= m; ++k) {
    const Ad fk = piece(a, k);
    if (!std::isfinite(fk.value()) || !fk.derivatives().allFinite())
      return OracleResult::failure("piece " + std::to_string(k) + " is not finite here");
    const Ad value = absolute ? ad_abs(fk) : fk;
    best.add(value);
    if (with_pieces) cuts.push_back(PieceCut{value.value(), value.derivatives()});
  }
  OracleResult r = OracleResult::success(best.f, best.g);
  if (with_pieces) {
    cuts.erase(cuts.begin() + best.index);  // the max itself is the answer's value and subgradient
    r.pieces = std::move(cuts);
  }
  return r;
}

/// A minimax problem: `f(x, with_pieces)` gives `evaluate` (false) and `evaluate_with_pieces`
/// (true).
inline LuksanVlcekProblem make_minimax(std::string name, std::string source, Eigen::VectorXd x0, double f_star,
                                       std::function<OracleResult(Vec, bool)> f) {
  LuksanVlcekProblem p = make(std::move(name), std::move(source), std::move(x0), f_star,
                              [f](Vec x) { return f(x, false); });
  p.evaluate_with_pieces = [f](Vec x) { return f(x, true); };
  return p;
}

}  // namespace frictopt::optim::detail
