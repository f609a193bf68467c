// SPDX-License-Identifier: MIT
#include "frictopt/cost/cost_functional.hpp"

#include <fmt/format.h>

#include <cmath>

#include "frictopt/core/error.hpp"
#include "frictopt/cost/cost_kind.hpp"

namespace frictopt::cost {
namespace {

sensitivity::CostPartials zero_partials(const CostInput& in) {
  sensitivity::CostPartials out;
  out.d_alpha = Eigen::VectorXd::Zero(in.alpha.size());
  out.d_displacement = Eigen::VectorXd::Zero(in.displacement.size());
  out.d_contact = Eigen::VectorXd::Zero(in.contact.z.size());
  return out;
}

class TargetNormalForce final : public CostFunctional {
 public:
  explicit TargetNormalForce(Eigen::VectorXd target) : target_(std::move(target)) {}
  std::string name() const override { return std::string(to_string(CostKind::kTargetPressure)); }
  sensitivity::CostPartials evaluate(const CostInput& in) const override {
    const Eigen::VectorXd lambda = in.contact.normal_forces();
    if (lambda.size() != target_.size())
      throw InvalidInput(fmt::format("cost target_pressure: target has {} entries; expected {} (contact nodes)",
                                     target_.size(), lambda.size()));
    sensitivity::CostPartials out = zero_partials(in);
    const Eigen::VectorXd r = lambda - target_;
    out.value = r.squaredNorm();
    const int dim = in.contact.dim;
    for (Eigen::Index i = 0; i < r.size(); ++i) out.d_contact(dim * i + dim - 1) = 2.0 * r(i);
    return out;
  }

 private:
  Eigen::VectorXd target_;
};

class NormalForcePower final : public CostFunctional {
 public:
  explicit NormalForcePower(double p) : p_(p) {
    if (!(p >= 2.0)) throw InvalidInput(fmt::format("cost normal_force_power: exponent = {}; expected >= 2", p));
  }
  std::string name() const override { return std::string(to_string(CostKind::kNormalForcePower)); }
  sensitivity::CostPartials evaluate(const CostInput& in) const override {
    sensitivity::CostPartials out = zero_partials(in);
    const int dim = in.contact.dim;
    out.value = 0.0;
    for (Eigen::Index i = 0; i < in.contact.num_nodes(); ++i) {
      const double lambda = std::max(in.contact.lambda(i), 0.0);
      out.value += std::pow(lambda, p_);
      out.d_contact(dim * i + dim - 1) = p_ * std::pow(lambda, p_ - 1.0);
    }
    return out;
  }

 private:
  double p_;
};

class Compliance final : public CostFunctional {
 public:
  std::string name() const override { return std::string(to_string(CostKind::kCompliance)); }
  sensitivity::CostPartials evaluate(const CostInput& in) const override {
    sensitivity::CostPartials out = zero_partials(in);
    const Eigen::VectorXd& u = in.displacement;
    const Eigen::VectorXd l = in.fem.traction_load(in.positions);
    const Eigen::VectorXd Au = in.fem.residual(in.positions, u) + l;  // A_full u
    out.value = -u.dot(Au) + l.dot(u);
    out.d_displacement = -2.0 * Au + l;
    // ∂/∂α(−uᵀA u + lᵀu) = −(uᵀ∂A u − uᵀ∂l): the fem kernel with p = u.
    out.d_alpha = -in.fem.shape_derivative(in.positions, u, u);
    return out;
  }
};

class PressureNorm final : public CostFunctional {
 public:
  explicit PressureNorm(double p) : p_(p) {
    if (!(p >= 2.0)) throw InvalidInput(fmt::format("cost pressure_norm: exponent = {}; expected >= 2", p));
  }
  std::string name() const override { return std::string(to_string(CostKind::kPressureNorm)); }
  sensitivity::CostPartials evaluate(const CostInput& in) const override {
    sensitivity::CostPartials out = zero_partials(in);
    const int dim = in.contact.dim;
    double sum = 0.0;
    for (Eigen::Index i = 0; i < in.contact.num_nodes(); ++i) {
      const double a = in.tributary_areas(i), pressure = std::max(in.contact.lambda(i), 0.0) / a;
      sum += a * std::pow(pressure, p_);
    }
    out.value = std::pow(sum, 1.0 / p_);
    if (sum <= 0.0) return out;  // no contact: the gradient is zero
    const double factor = std::pow(sum, 1.0 / p_ - 1.0);
    for (Eigen::Index i = 0; i < in.contact.num_nodes(); ++i) {
      const double a = in.tributary_areas(i), pressure = std::max(in.contact.lambda(i), 0.0) / a;
      out.d_contact(dim * i + dim - 1) = factor * std::pow(pressure, p_ - 1.0);
    }
    return out;
  }

 private:
  double p_;
};

class TotalSlip final : public CostFunctional {
 public:
  explicit TotalSlip(double delta) : delta_(delta) {
    if (!(delta > 0)) throw InvalidInput(fmt::format("cost total_slip: smoothing = {}; expected > 0", delta));
  }
  std::string name() const override { return std::string(to_string(CostKind::kTotalSlip)); }
  sensitivity::CostPartials evaluate(const CostInput& in) const override {
    sensitivity::CostPartials out = zero_partials(in);
    const int dim = in.contact.dim;
    out.value = 0.0;
    for (Eigen::Index i = 0; i < in.boundary.num_nodes(); ++i) {
      const int node = in.boundary.nodes()[static_cast<std::size_t>(i)];
      // u_t in the foundation's frame: (t_c·u_node)_c (standard foundation: the x1 (, x2) components).
      const Eigen::MatrixXd& tangents = in.boundary.foundation().frame.tangents;
      const Eigen::VectorXd ut = tangents.transpose() * in.displacement.segment(node * dim, dim);
      const double r = std::sqrt(ut.squaredNorm() + delta_ * delta_);
      out.value += r - delta_;
      out.d_displacement.segment(node * dim, dim) = tangents * ut / r;
    }
    return out;
  }

 private:
  double delta_;
};

class TractionUniformity final : public CostFunctional {
 public:
  explicit TractionUniformity(Eigen::VectorXd target) : target_(std::move(target)) {
    if (target_.size() > 2 || !target_.allFinite())
      throw InvalidInput(fmt::format("cost traction_uniformity: target has {} entries (finite: {}); expected 1 (2D) or "
                                     "2 (3D) finite components, or none for the mean traction",
                                     target_.size(), target_.allFinite()));
  }
  std::string name() const override { return std::string(to_string(CostKind::kTractionUniformity)); }
  sensitivity::CostPartials evaluate(const CostInput& in) const override {
    sensitivity::CostPartials out = zero_partials(in);
    const int dim = in.contact.dim, nt = dim - 1;
    const Eigen::Index p = in.contact.num_nodes();
    if (target_.size() && target_.size() != nt)
      throw InvalidInput(fmt::format("cost traction_uniformity: target has {} components; expected {} for a {}D body",
                                     target_.size(), nt, dim));
    // τ_i = −q_i: the tangential nodal force on the body; t_i = τ_i / a_i.
    const auto tau = [&](Eigen::Index i, int c) { return -in.contact.z(dim * i + c); };
    Eigen::VectorXd mean = Eigen::VectorXd::Zero(nt);
    if (target_.size()) {
      mean = target_;
    } else {
      for (Eigen::Index i = 0; i < p; ++i)
        for (int c = 0; c < nt; ++c) mean(c) += tau(i, c);
      mean /= in.tributary_areas.sum();
    }
    out.value = 0.0;
    for (Eigen::Index i = 0; i < p; ++i) {
      const double a = in.tributary_areas(i);
      for (int c = 0; c < nt; ++c) {
        const double deviation = tau(i, c) / a - mean(c);
        out.value += a * deviation * deviation;
        out.d_contact(dim * i + c) = -2.0 * deviation;  // ∂J/∂q = −∂J/∂τ
      }
    }
    return out;
  }

 private:
  Eigen::VectorXd target_;
};

}  // namespace

std::unique_ptr<CostFunctional> make_target_normal_force(Eigen::VectorXd target) {
  return std::make_unique<TargetNormalForce>(std::move(target));
}
std::unique_ptr<CostFunctional> make_normal_force_power(double exponent) {
  return std::make_unique<NormalForcePower>(exponent);
}
std::unique_ptr<CostFunctional> make_compliance() { return std::make_unique<Compliance>(); }
std::unique_ptr<CostFunctional> make_pressure_norm(double exponent) { return std::make_unique<PressureNorm>(exponent); }
std::unique_ptr<CostFunctional> make_total_slip(double smoothing) { return std::make_unique<TotalSlip>(smoothing); }
std::unique_ptr<CostFunctional> make_traction_uniformity(Eigen::VectorXd target) {
  return std::make_unique<TractionUniformity>(std::move(target));
}

}  // namespace frictopt::cost
