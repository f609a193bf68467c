// SPDX-License-Identifier: MIT
#include "frictopt/io/study_setup.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "frictopt/core/error.hpp"
#include "frictopt/mesh/face.hpp"

namespace frictopt::io {
namespace {
mesh::Face to_mesh_face(Face face) {
  switch (face) {
    case Face::kLeft:
      return mesh::Face::kLeft;
    case Face::kRight:
      return mesh::Face::kRight;
    case Face::kFront:
      return mesh::Face::kFront;
    case Face::kBack:
      return mesh::Face::kBack;
    case Face::kTop:
      return mesh::Face::kTop;
  }
  return mesh::Face::kTop;
}

// FrictionSpec → FrictionLaw (DESIGN.md, "Friction sets"); the law validates convexity itself.
contact::FrictionLaw make_friction_law(const CaseDescription& c) {
  const FrictionSpec& f = c.contact->friction;
  const int dim = c.geometry.dim;
  const int n = f.n.value_or(16);
  try {
    switch (f.kind) {
      case FrictionKind::kNone:
        return dim == 2 ? contact::FrictionLaw::interval(0.0, 0.0) : contact::FrictionLaw::disc(0.0);
      case FrictionKind::kIsotropic:
        return dim == 2 ? contact::FrictionLaw::interval(*f.mu, *f.mu) : contact::FrictionLaw::regular_polygon(*f.mu, n);
      case FrictionKind::kPolygon:
        return dim == 2 ? contact::FrictionLaw::interval(*f.mu_minus, *f.mu_plus)
                        : contact::FrictionLaw::polygon(f.mu_vertices);
      case FrictionKind::kEllipse: return contact::FrictionLaw::ellipse_polygon(*f.mu_x, *f.mu_y, n);
      case FrictionKind::kEllipseExact: return contact::FrictionLaw::ellipse(*f.mu_x, *f.mu_y);
      case FrictionKind::kDiscExact: return contact::FrictionLaw::disc(*f.mu);
    }
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("{}: contact.friction: {}", c.origin, e.what()));
  }
  return contact::FrictionLaw::disc(0.0);
}
}  // namespace

study::BodyDefinition make_body_definition(const CaseDescription& c) {
  study::BodyDefinition body;
  body.name =
      c.output.name.empty() ? std::filesystem::path(c.origin).stem().string() : c.output.name;
  const int dim = c.geometry.dim;
  body.shape =
      dim == 2 ? shape::BezierShape::curve(c.geometry.a, c.design.control_points[0])
               : shape::BezierShape::surface(c.geometry.a, c.geometry.b, c.design.control_points[0],
                                             c.design.control_points[1]);
  body.height = c.geometry.height;
  body.resolution.cells =
      dim == 2 ? std::array<int, 3>{c.mesh.cells[0], 0, c.mesh.cells[1]}
               : std::array<int, 3>{c.mesh.cells[0], c.mesh.cells[1], c.mesh.cells[2]};
  body.resolution.grading = c.mesh.grading;
  body.material.young = c.material.young;
  body.material.poisson = c.material.poisson;
  body.material.plane_model = c.material.model == PlaneModel::kPlaneStress
                                  ? fem::PlaneModel::kPlaneStress
                                  : fem::PlaneModel::kPlaneStrain;
  for (const DirichletSpec& d : c.dirichlet)
    body.dirichlet.push_back({std::string(mesh::to_string(to_mesh_face(d.face))), d.components, d.displacement});
  for (const LoadSpec& l : c.loads)
    body.tractions.push_back({std::string(mesh::to_string(to_mesh_face(l.face))), l.traction});
  body.admissible.upper_bound = c.design.upper_bound;
  body.admissible.slope_bound = c.design.slope_bound;
  body.admissible.volume = c.design.volume;
  body.admissible.height = c.geometry.height;
  body.admissible.slope_scaling = c.design.slope_scaling == SlopeScaling::kExact
                                      ? shape::SlopeScaling::kExact
                                      : shape::SlopeScaling::kThesis;
  body.initial_design = c.design.initial;
  if (c.contact) {
    study::ContactDefinition contact_definition;
    contact_definition.law = make_friction_law(c);
    auto& coulomb = contact_definition.coulomb;
    if (c.solver.coulomb.max_iterations) coulomb.max_iterations = *c.solver.coulomb.max_iterations;
    if (c.solver.coulomb.relative_tolerance) coulomb.relative_tolerance = *c.solver.coulomb.relative_tolerance;
    if (c.solver.qp.max_iterations) coulomb.tresca.max_iterations = *c.solver.qp.max_iterations;
    if (c.solver.qp.relative_tolerance) coulomb.tresca.relative_tolerance = *c.solver.qp.relative_tolerance;
    body.contact = contact_definition;
  }
  return body;
}

study::CostDefinition make_cost_definition(const CaseDescription& c) {
  if (!c.cost)
    throw InvalidInput(fmt::format("{}: no [cost] table; expected one with kind = target_pressure, "
                                   "normal_force_power, compliance, pressure_norm, total_slip or traction_uniformity",
                                   c.origin));
  using Kind = study::CostDefinition::Kind;
  study::CostDefinition d;
  switch (c.cost->kind) {
    case CostKind::kTargetPressure: d.kind = Kind::kTargetPressure; break;
    case CostKind::kNormalForcePower: d.kind = Kind::kNormalForcePower; break;
    case CostKind::kCompliance: d.kind = Kind::kCompliance; break;
    case CostKind::kPressureNorm: d.kind = Kind::kPressureNorm; d.exponent = 8.0; break;
    case CostKind::kTotalSlip: d.kind = Kind::kTotalSlip; break;
    case CostKind::kTractionUniformity:
      d.kind = Kind::kTractionUniformity;
      d.target_traction = Eigen::Map<const Eigen::VectorXd>(c.cost->target_traction.data(),
                                                            static_cast<Eigen::Index>(c.cost->target_traction.size()));
      d.target_traction_initial_mean = c.cost->target_traction_initial_mean;
      break;
  }
  if (c.cost->target_pressure) d.target_pressure = *c.cost->target_pressure;
  if (c.cost->exponent) d.exponent = *c.cost->exponent;
  if (c.cost->smoothing) d.smoothing = *c.cost->smoothing;
  return d;
}

}  // namespace frictopt::io
