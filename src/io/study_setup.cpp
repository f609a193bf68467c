// SPDX-License-Identifier: MIT
#include "frictopt/io/study_setup.hpp"

#include <filesystem>

namespace frictopt::io {
namespace {
mesh::Face to_mesh_face(Face face) {
  switch (face) {
    case Face::kLeft: return mesh::Face::kLeft;
    case Face::kRight: return mesh::Face::kRight;
    case Face::kFront: return mesh::Face::kFront;
    case Face::kBack: return mesh::Face::kBack;
    case Face::kTop: return mesh::Face::kTop;
  }
  return mesh::Face::kTop;
}
}  // namespace

study::BodyDefinition make_body_definition(const CaseDescription& c) {
  study::BodyDefinition body;
  body.name = c.output.name.empty() ? std::filesystem::path(c.origin).stem().string() : c.output.name;
  const int dim = c.geometry.dim;
  body.shape = dim == 2 ? shape::BezierShape::curve(c.geometry.a, c.design.control_points[0])
                        : shape::BezierShape::surface(c.geometry.a, c.geometry.b, c.design.control_points[0],
                                                      c.design.control_points[1]);
  body.height = c.geometry.height;
  body.resolution.cells = dim == 2 ? std::array<int, 3>{c.mesh.cells[0], 0, c.mesh.cells[1]}
                                   : std::array<int, 3>{c.mesh.cells[0], c.mesh.cells[1], c.mesh.cells[2]};
  body.resolution.grading = c.mesh.grading;
  body.material.young = c.material.young;
  body.material.poisson = c.material.poisson;
  body.material.plane_model =
      c.material.model == PlaneModel::kPlaneStress ? fem::PlaneModel::kPlaneStress : fem::PlaneModel::kPlaneStrain;
  for (const DirichletSpec& d : c.dirichlet)
    body.dirichlet.push_back({to_mesh_face(d.face), d.components, d.displacement});
  for (const LoadSpec& l : c.loads) body.tractions.push_back({to_mesh_face(l.face), l.traction});
  body.admissible.upper_bound = c.design.upper_bound;
  body.admissible.slope_bound = c.design.slope_bound;
  body.admissible.volume = c.design.volume;
  body.admissible.height = c.geometry.height;
  body.admissible.slope_scaling =
      c.design.slope_scaling == SlopeScaling::kExact ? shape::SlopeScaling::kExact : shape::SlopeScaling::kThesis;
  body.initial_design = c.design.initial;
  return body;
}

}  // namespace frictopt::io
