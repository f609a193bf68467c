// SPDX-License-Identifier: MIT
// The numbers a tribologist reads off a contact solution: total normal and tangential force,
// their ratio, contact / stick / slip areas and node counts, the stick zone's centroid and an
// equivalent radius. Computed from the nodal dual variables z_i = (q_i, λ_i)
// (docs/theory/state-problem.md §1, §5) and the tributary areas of the contact nodes; the
// conventions are in docs/contact.md.
#pragma once

#include <Eigen/Core>
#include <string>

#include "frictopt/contact/contact_state.hpp"
#include "frictopt/core/status.hpp"

namespace frictopt::contact {

/// Resultants of one contact state. Forces are those the foundation exerts on the body:
/// normal force Σλ_i (upward) and tangential force Σ τ_i = −Σ q_i (τ_i opposes the slip;
/// docs/theory/state-problem.md §1). Areas are sums of tributary areas a_i of the nodes in each
/// class (3D: m², 2D: m per metre of thickness). The stick zone's centroid is the a_i-weighted mean
/// of the in-plane node coordinates of stick nodes; its equivalent radius is that of a disc of the
/// stick area (3D: √(A/π)) or the half-width of a strip (2D: A/2), the quantity Cattaneo–Mindlin's
/// c is compared with.
struct ContactResultants {
  int dim = 3;
  double normal_force = 0.0;                                   ///< P = Σλ_i [N; 2D: N/m]
  Eigen::Vector2d tangential_force = Eigen::Vector2d::Zero();  ///< T = Σ τ_i (2D: component 1 is 0)
  double tangential_force_norm = 0.0;                          ///< |T|
  double force_ratio = kNaN;                                   ///< |T| / P (NaN when P = 0)
  /// The same total force in global axes, Σ Fᵀz_i with F the foundation's frame rows
  /// (ContactBoundary::frame_rows): P n + T_1 t1 (+ T_2 t2). 2D: component 2 is 0.
  Eigen::Vector3d global_force = Eigen::Vector3d::Zero();
  double contact_area = 0.0;  ///< Σ a_i over nodes with a normal force (stick + slip)
  int num_stick = 0;
  int num_slip = 0;
  int num_separated = 0;
  double stick_area = 0.0;
  double slip_area = 0.0;
  double separated_area = 0.0;
  /// a_i-weighted mean in-plane position of the stick nodes (NaN without stick nodes).
  Eigen::Vector2d stick_centroid = Eigen::Vector2d::Constant(kNaN);
  double stick_equivalent_radius = 0.0;    ///< 3D √(A_stick/π), 2D A_stick/2
  double contact_equivalent_radius = 0.0;  ///< the same for the contact area
  /// One line for logs and the CLI.
  std::string brief_report() const;
};

/// Resultants of `state` (classified: state.nodes filled) for contact nodes with tributary
/// areas `areas` (p) and in-plane coordinates `plane` (p × dim−1), forces in the foundation's
/// frame and, through `frame_rows` (dim × dim, ContactBoundary::frame_rows), in global axes.
/// Throws InvalidInput on size mismatches.
[[nodiscard]] ContactResultants contact_resultants(const ContactState& state,
                                                   const Eigen::Ref<const Eigen::VectorXd>& areas,
                                                   const Eigen::Ref<const Eigen::MatrixXd>& plane,
                                                   const Eigen::Ref<const Eigen::MatrixXd>& frame_rows);
/// The same for the standard foundation (frame rows diag(−1, (−1,) 1)).
[[nodiscard]] ContactResultants contact_resultants(const ContactState& state,
                                                   const Eigen::Ref<const Eigen::VectorXd>& areas,
                                                   const Eigen::Ref<const Eigen::MatrixXd>& plane);

}  // namespace frictopt::contact
