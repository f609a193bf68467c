// SPDX-License-Identifier: MIT
#include "frictopt/study/orientation_design.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "frictopt/core/error.hpp"
#include "frictopt/sensitivity/friction_parameters.hpp"
#include "frictopt/sensitivity/parameter_sensitivity.hpp"

namespace frictopt::study {
namespace {
double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }
}  // namespace

OrientationDesign::OrientationDesign(const OrientationDesignDefinition& definition, const contact::FrictionLaw& law,
                                     double design_range)
    : definition_(definition), law_(law) {
  if (law.dim() != 3)
    throw InvalidInput("design.friction_orientation = true: a 2D interval law has no orientation (its tangent space is "
                       "a line); expected a 3D anisotropic law (polygon, ellipse, ellipse_exact) or "
                       "friction_orientation = false");
  if (law.is_isotropic())
    throw InvalidInput(fmt::format("design.friction_orientation = true: the law {} is isotropic, Θ does not depend on "
                                   "its orientation; expected an anisotropic 3D law (polygon, ellipse with mu_x != "
                                   "mu_y) or friction_orientation = false",
                                   law.describe()));
  const double lo = definition.lower, hi = definition.upper;
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi))
    throw InvalidInput(fmt::format("design.orientation_lower_deg = {}, orientation_upper_deg = {}: expected finite "
                                   "bounds with orientation_lower_deg < orientation_upper_deg",
                                   degrees(lo), degrees(hi)));
  const double phi0 = law.orientation();
  if (!(phi0 >= lo && phi0 <= hi))
    throw InvalidInput(fmt::format("contact.friction.orientation_deg = {} (the initial orientation): outside the "
                                   "design bounds; expected orientation_lower_deg = {} <= orientation_deg <= "
                                   "orientation_upper_deg = {}",
                                   degrees(phi0), degrees(lo), degrees(hi)));
  if (!(design_range > 0.0))
    throw InvalidInput(fmt::format("design.upper_bound = {}: the orientation's scale needs a design range C0 > 0",
                                   design_range));
  scale_ = design_range / (hi - lo);
}

contact::FrictionLaw OrientationDesign::law_at(double phi) const {
  if (phi == law_.orientation()) return law_;
  return law_.rotated(phi - law_.orientation());
}

contact::FrictionLaw OrientationDesign::law_for_variable(double s) const {
  return s == variable(law_.orientation()) ? law_ : law_at(angle(s));
}

LinearConstraints OrientationDesign::extend(const LinearConstraints& upsilon) const {
  const Eigen::Index d = upsilon.dimension();
  LinearConstraints out = upsilon;
  out.lower.conservativeResize(d + 1);
  out.upper.conservativeResize(d + 1);
  out.lower(d) = variable(definition_.lower);
  out.upper(d) = variable(definition_.upper);
  if (upsilon.A_in.rows() > 0) {
    out.A_in.conservativeResize(Eigen::NoChange, d + 1);
    out.A_in.col(d).setZero();
  } else {
    out.A_in.resize(0, d + 1);
  }
  if (upsilon.A_eq.rows() > 0) {
    out.A_eq.conservativeResize(Eigen::NoChange, d + 1);
    out.A_eq.col(d).setZero();
  } else {
    out.A_eq.resize(0, d + 1);
  }
  return out;
}

Eigen::VectorXd OrientationDesign::initial_design(const Eigen::VectorXd& alpha0) const {
  Eigen::VectorXd x(alpha0.size() + 1);
  x << alpha0, variable(law_.orientation());
  return x;
}

double OrientationDesign::derivative(const sensitivity::Piece& piece, const contact::FrictionLaw& law,
                                     const contact::ContactState& state, const Eigen::VectorXd& psi_z) const {
  const Eigen::MatrixXd rows =
      sensitivity::friction_parameter_rows(piece, law, state, sensitivity::orientation_parameter(law));
  return (rows.transpose() * psi_z)(0) / scale_;
}

void append_orientation_derivative(const OrientationDesign* design, const contact::FrictionLaw& law,
                                   const sensitivity::Piece& piece, const contact::ContactState& state,
                                   sensitivity::AdjointSensitivity::Result& result) {
  if (!design || result.summary.status != Status::kConverged) return;
  const Eigen::Index d = result.subgradient.size();
  result.subgradient.conservativeResize(d + 1);
  result.subgradient(d) = design->derivative(piece, law, state, result.psi_z);
}

}  // namespace frictopt::study
