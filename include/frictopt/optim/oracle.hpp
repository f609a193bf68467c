// SPDX-License-Identifier: MIT
// The only thing the optimizers know about a problem (docs/theory/bundle-trust.md §1): at a point
// x, the value f(x) and one arbitrary Clarke subgradient g ∈ ∂f(x) — or the news that f cannot be
// evaluated there (e.g. the contact solver failed), in which case the method shortens its step.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace frictopt::optim {

/// A further linearization of a max-type f = max_i φ_i at the same x: φ_i(x) <= f(x) and one
/// subgradient of φ_i there (docs/optim.md, "Cuts of the pieces of a max").
struct PieceCut {
  double value = 0.0;
  Eigen::VectorXd subgradient;
};

/// One oracle answer. When `ok` is false, `value` and `subgradient` are ignored and `message`
/// says why; a non-finite value or subgradient with `ok == true` is treated the same way by the
/// optimizers (counted in Summary::failed_evaluations).
struct OracleResult {
  bool ok = true;
  double value = 0.0;
  Eigen::VectorXd subgradient;  ///< size n; one element of ∂f(x) (or of a pseudodifferential)
  std::string message;
  /// Optional, for f = max_i φ_i (e.g. a worst case over load cases): cuts of the pieces φ_i
  /// other than the one `value`/`subgradient` belong to. The bundle method adds each as a cut of
  /// its own — a disaggregated model of the max (Kiwiel 1985) — where one subgradient of f alone
  /// would leave every other piece to be discovered by null steps. Pieces that are not finite
  /// or have the wrong size are ignored; values above `value` are not allowed (InvalidInput).
  std::vector<PieceCut> pieces;

  /// A successful answer.
  [[nodiscard]] static OracleResult success(double value, Eigen::VectorXd subgradient) {
    return OracleResult{true, value, std::move(subgradient), {}, {}};
  }
  /// "Could not evaluate here", with the reason.
  [[nodiscard]] static OracleResult failure(std::string reason) {
    return OracleResult{false, 0.0, {}, std::move(reason), {}};
  }
};

/// A function f: ℝⁿ → ℝ seen through values and subgradients. Implementations may cache
/// (`study` caches per design); `evaluate` is not const for that reason. The optimizers call it
/// from one thread and only at points inside the feasible set.
class Oracle {
 public:
  virtual ~Oracle() = default;
  [[nodiscard]] virtual OracleResult evaluate(const Eigen::Ref<const Eigen::VectorXd>& x) = 0;
};

/// Adapts a callable (lambda) to Oracle. The callable is copied into the adapter.
class FunctionOracle final : public Oracle {
 public:
  using Function = std::function<OracleResult(const Eigen::Ref<const Eigen::VectorXd>&)>;
  explicit FunctionOracle(Function f) : f_(std::move(f)) {}
  [[nodiscard]] OracleResult evaluate(const Eigen::Ref<const Eigen::VectorXd>& x) override {
    return f_(x);
  }

 private:
  Function f_;
};

}  // namespace frictopt::optim
