// SPDX-License-Identifier: MIT
#include "frictopt/core/linear_constraints.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "frictopt/core/error.hpp"

namespace frictopt {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string dims(Eigen::Index r, Eigen::Index c) {
  std::ostringstream s;
  s << r << "x" << c;
  return s.str();
}

std::string number(double v) {
  std::ostringstream s;
  s << std::setprecision(6) << v;
  return s.str();
}
}  // namespace

bool LinearConstraints::empty() const {
  const bool no_lower = lower.size() == 0 || (lower.array() == -kInf).all();
  const bool no_upper = upper.size() == 0 || (upper.array() == kInf).all();
  return no_lower && no_upper && A_in.rows() == 0 && A_eq.rows() == 0;
}

void LinearConstraints::validate(Eigen::Index n) const {
  const std::string nn = std::to_string(n);
  if (lower.size() != 0 && lower.size() != n)
    throw InvalidInput("LinearConstraints::lower has size " + std::to_string(lower.size()) +
                       "; expected 0 or n = " + nn);
  if (upper.size() != 0 && upper.size() != n)
    throw InvalidInput("LinearConstraints::upper has size " + std::to_string(upper.size()) +
                       "; expected 0 or n = " + nn);
  for (Eigen::Index i = 0; i < lower.size(); ++i) {
    if (std::isnan(lower(i)) || lower(i) == kInf)
      throw InvalidInput("LinearConstraints::lower[" + std::to_string(i) + "] = " +
                         std::to_string(lower(i)) + "; expected a finite number or -inf");
  }
  for (Eigen::Index i = 0; i < upper.size(); ++i) {
    if (std::isnan(upper(i)) || upper(i) == -kInf)
      throw InvalidInput("LinearConstraints::upper[" + std::to_string(i) + "] = " +
                         std::to_string(upper(i)) + "; expected a finite number or +inf");
    if (lower.size() == n && lower(i) > upper(i))
      throw InvalidInput("LinearConstraints: lower[" + std::to_string(i) + "] = " +
                         std::to_string(lower(i)) + " > upper[" + std::to_string(i) + "] = " +
                         std::to_string(upper(i)) + "; expected lower <= upper (empty box)");
  }
  if (A_in.rows() > 0 && A_in.cols() != n)
    throw InvalidInput("LinearConstraints::A_in is " + dims(A_in.rows(), A_in.cols()) +
                       "; expected m x " + nn);
  if (b_in.size() != A_in.rows())
    throw InvalidInput("LinearConstraints::b_in has size " + std::to_string(b_in.size()) +
                       "; expected A_in.rows() = " + std::to_string(A_in.rows()));
  if (A_eq.rows() > 0 && A_eq.cols() != n)
    throw InvalidInput("LinearConstraints::A_eq is " + dims(A_eq.rows(), A_eq.cols()) +
                       "; expected p x " + nn);
  if (b_eq.size() != A_eq.rows())
    throw InvalidInput("LinearConstraints::b_eq has size " + std::to_string(b_eq.size()) +
                       "; expected A_eq.rows() = " + std::to_string(A_eq.rows()));
  if (!A_in.allFinite() || !b_in.allFinite() || !A_eq.allFinite() || !b_eq.allFinite())
    throw InvalidInput("LinearConstraints: non-finite entry in A_in, b_in, A_eq or b_eq; expected finite numbers");
}

double LinearConstraints::max_violation(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  double v = 0.0;
  for (Eigen::Index i = 0; i < lower.size(); ++i) v = std::max(v, lower(i) - x(i));
  for (Eigen::Index i = 0; i < upper.size(); ++i) v = std::max(v, x(i) - upper(i));
  if (A_in.rows() > 0) v = std::max(v, (A_in * x - b_in).maxCoeff());
  if (A_eq.rows() > 0) v = std::max(v, (A_eq * x - b_eq).lpNorm<Eigen::Infinity>());
  return v;
}

std::string LinearConstraints::describe_violation(const Eigen::Ref<const Eigen::VectorXd>& x, double tol) const {
  double worst = tol;
  std::string what;
  const auto var = [&](Eigen::Index k) { return variable_name + "[" + std::to_string(k) + "] = " + number(x(k)); };
  for (Eigen::Index k = 0; k < lower.size(); ++k) {
    if (lower(k) - x(k) > worst) {
      worst = lower(k) - x(k);
      what = var(k) + "; expected >= " + number(lower(k));
    }
  }
  for (Eigen::Index k = 0; k < upper.size(); ++k) {
    if (x(k) - upper(k) > worst) {
      worst = x(k) - upper(k);
      what = var(k) + "; expected <= " + number(upper(k));
    }
  }
  for (Eigen::Index r = 0; r < A_in.rows(); ++r) {
    const double lhs = A_in.row(r).dot(x);
    if (lhs - b_in(r) > worst) {
      worst = lhs - b_in(r);
      const std::string name = static_cast<std::size_t>(r) < inequality_names.size()
                                   ? inequality_names[static_cast<std::size_t>(r)]
                                   : "A_in[" + std::to_string(r) + "]";
      what = name + ": value " + number(lhs) + "; expected <= " + number(b_in(r));
    }
  }
  for (Eigen::Index r = 0; r < A_eq.rows(); ++r) {
    const double lhs = A_eq.row(r).dot(x);
    if (std::abs(lhs - b_eq(r)) > worst) {
      worst = std::abs(lhs - b_eq(r));
      const std::string name = static_cast<std::size_t>(r) < equality_names.size()
                                   ? equality_names[static_cast<std::size_t>(r)]
                                   : "A_eq[" + std::to_string(r) + "]";
      what = name + " = " + number(lhs) + "; expected " + number(b_eq(r));
    }
  }
  return what;
}

}  // namespace frictopt
