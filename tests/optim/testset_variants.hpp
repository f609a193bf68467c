// SPDX-License-Identifier: MIT
// The variants of the Lukšan–Vlček test set on which docs/optim-testset.md ("Units, shifts and
// last bits") checks that the bundle trust method's decisions do not depend on the units of f
// and x nor on the last bits of f: the same problem written as a·f(x̃/c) + b in the variables
// x̃ = c·x. Used by the slow test (luksan_vlcek_slow_test.cpp), the quick invariance tests and
// bench/optim/optim_testset_variants.cpp. Header-only: test code.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "frictopt/optim/oracle.hpp"
#include "testset/luksan_vlcek.hpp"

namespace frictopt::optim::testset {

/// f̃(x̃) = a·f(x̃/c) + b, with b = shift·max(1, |f*|); `pieces` gives the minimax problems their
/// structured oracle (LuksanVlcekProblem::evaluate_with_pieces).
struct Variant {
  std::string name;
  double a = 1.0;
  double shift = 0.0;
  double c = 1.0;
  bool pieces = false;
};

/// plain, structured, f·1e±3, x·1e±3, f + 1e3·max(1, |f*|) and the last-bit perturbations
/// f·(1 + k·2⁻⁴⁰), k = 1…8.
inline std::vector<Variant> variants() {
  std::vector<Variant> v{{"plain", 1.0, 0.0, 1.0, false},   {"structured", 1.0, 0.0, 1.0, true},
                         {"f*1e-3", 1e-3, 0.0, 1.0, false}, {"f*1e3", 1e3, 0.0, 1.0, false},
                         {"x*1e-3", 1.0, 0.0, 1e-3, false}, {"x*1e3", 1.0, 0.0, 1e3, false},
                         {"f+1e3|f*|", 1.0, 1e3, 1.0, false}};
  for (int k = 1; k <= 8; ++k)
    v.push_back({"f*(1+" + std::to_string(k) + "u)", 1.0 + k * std::ldexp(1.0, -40), 0.0, 1.0, false});
  return v;
}

/// The variant of p: its oracle, start and constraints (x̃ = c·x), and `shift` b. Accuracy is
/// judged on the original problem: original_value(f̃) = (f̃ − b)/a against p.f_star.
struct VariantProblem {
  LuksanVlcekProblem problem;
  double a = 1.0;
  double b = 0.0;
  [[nodiscard]] double original_value(double f) const { return (f - b) / a; }
};

inline VariantProblem make_variant(const LuksanVlcekProblem& p, const Variant& v) {
  VariantProblem out;
  out.problem = v.c != 1.0 ? with_scaled_variables(p, v.c) : p;
  out.a = v.a;
  out.b = v.shift * std::max(1.0, std::abs(p.f_star));
  FunctionOracle::Function base =
      v.pieces && out.problem.evaluate_with_pieces ? out.problem.evaluate_with_pieces : out.problem.evaluate;
  if (v.a != 1.0 || out.b != 0.0) {
    const double a = out.a, b = out.b;
    base = [base, a, b](const Eigen::Ref<const Eigen::VectorXd>& x) {
      OracleResult r = base(x);
      if (r.ok) {
        r.value = a * r.value + b;
        r.subgradient *= a;
        for (PieceCut& piece : r.pieces) {
          piece.value = a * piece.value + b;
          piece.subgradient *= a;
        }
      }
      return r;
    };
  }
  out.problem.evaluate = base;
  out.problem.name = p.name + "/" + v.name;
  return out;
}

/// The 40 problems of TEST19 and TEST22.
inline std::vector<LuksanVlcekProblem> forty() {
  std::vector<LuksanVlcekProblem> p = luksan_vlcek_unconstrained();
  for (auto& q : luksan_vlcek_constrained()) p.push_back(q);
  return p;
}

}  // namespace frictopt::optim::testset
