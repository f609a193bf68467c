// SPDX-License-Identifier: MIT
// The accuracy test of the Lukšan–Vlček problems, their scaled variants and the lookup by name.
// The problems themselves are in luksan_vlcek_test19.cpp and luksan_vlcek_test22.cpp.
#include "testset/luksan_vlcek.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "frictopt/core/error.hpp"

namespace frictopt::optim {

double LuksanVlcekProblem::relative_error(double f) const {
  return std::abs(f - f_star) / std::max(value_unit, std::abs(f_star));
}

bool LuksanVlcekProblem::solved(double f, double tolerance) const {
  return relative_error(f) <= tolerance;
}

namespace {

std::string factor_name(double c) {
  std::ostringstream s;
  s << c;
  return s.str();
}

void require_positive(double c, const char* who) {
  if (!(c > 0.0) || !std::isfinite(c))
    throw InvalidInput(std::string(who) + ": scale factor = " + std::to_string(c) + "; expected finite and > 0");
}

}  // namespace

LuksanVlcekProblem with_scaled_values(const LuksanVlcekProblem& p, double c) {
  require_positive(c, "with_scaled_values");
  LuksanVlcekProblem q = p;
  q.name = p.name + "_f*" + factor_name(c);
  q.source = p.source + ", f·" + factor_name(c);
  q.f_star = c * p.f_star;
  q.value_unit = c * p.value_unit;
  const auto scaled = [c](const FunctionOracle::Function& f) -> FunctionOracle::Function {
    if (!f) return {};
    return [f, c](const Eigen::Ref<const Eigen::VectorXd>& x) {
      OracleResult r = f(x);
      if (r.ok) {
        r.value *= c;
        r.subgradient *= c;
        for (PieceCut& piece : r.pieces) {
          piece.value *= c;
          piece.subgradient *= c;
        }
      }
      return r;
    };
  };
  q.evaluate = scaled(p.evaluate);
  q.evaluate_with_pieces = scaled(p.evaluate_with_pieces);
  return q;
}

LuksanVlcekProblem with_scaled_variables(const LuksanVlcekProblem& p, double c) {
  require_positive(c, "with_scaled_variables");
  LuksanVlcekProblem q = p;
  q.name = p.name + "_x*" + factor_name(c);
  q.source = p.source + ", x·" + factor_name(c);
  q.x0 = c * p.x0;
  // x̃ = c x: bounds scale by c, rows A x ≤ b become (A/c) x̃ ≤ b.
  LinearConstraints& k = q.constraints;
  if (k.lower.size() > 0) k.lower *= c;
  if (k.upper.size() > 0) k.upper *= c;
  if (k.A_in.size() > 0) k.A_in /= c;
  if (k.A_eq.size() > 0) k.A_eq /= c;
  const auto scaled = [c](const FunctionOracle::Function& f) -> FunctionOracle::Function {
    if (!f) return {};
    return [f, c](const Eigen::Ref<const Eigen::VectorXd>& x) {
      OracleResult r = f(x / c);
      if (r.ok) {
        r.subgradient /= c;  // ∂f̃(x̃) = ∂f(x̃/c) / c
        for (PieceCut& piece : r.pieces) piece.subgradient /= c;
      }
      return r;
    };
  };
  q.evaluate = scaled(p.evaluate);
  q.evaluate_with_pieces = scaled(p.evaluate_with_pieces);
  return q;
}

std::vector<LuksanVlcekProblem> luksan_vlcek_scaled_variants() {
  // Several problems of both sets, smooth and nonsmooth, with and without constraints.
  const char* names[] = {"CB2", "Rosenbrock", "Maxquad", "Shor", "L1HILB", "MAD1", "Pentagon", "Wong2"};
  std::vector<LuksanVlcekProblem> out;
  for (const char* name : names) {
    const LuksanVlcekProblem p = luksan_vlcek_problem(name);
    for (double c : {1e-3, 1e3}) {
      out.push_back(with_scaled_values(p, c));
      out.push_back(with_scaled_variables(p, c));
    }
  }
  return out;
}

LuksanVlcekProblem luksan_vlcek_problem(std::string_view name) {
  std::string names;
  for (auto set : {luksan_vlcek_unconstrained(), luksan_vlcek_constrained()}) {
    for (auto& p : set) {
      if (p.name == name) return p;
      names += (names.empty() ? "" : ", ") + p.name;
    }
  }
  // Variants: "<problem>_f*c" or "<problem>_x*c".
  const std::size_t at = name.rfind('*');
  if (at != std::string_view::npos && at >= 2 && name[at - 2] == '_') {
    const LuksanVlcekProblem base = luksan_vlcek_problem(name.substr(0, at - 2));
    const double c = std::stod(std::string(name.substr(at + 1)));
    return name[at - 1] == 'f' ? with_scaled_values(base, c) : with_scaled_variables(base, c);
  }
  throw InvalidInput("luksan_vlcek_problem: unknown name '" + std::string(name) + "'; expected one of " +
                     names + " or a variant <name>_f*<c> / <name>_x*<c>");
}

}  // namespace frictopt::optim
