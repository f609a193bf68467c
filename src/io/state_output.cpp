// SPDX-License-Identifier: MIT
#include "frictopt/io/state_output.hpp"

namespace frictopt::io {

VtuGrid make_state_grid(const study::ElasticBody& body, const study::BodyState& state) {
  const mesh::StructuredMesh& m = body.mesh();
  const int dim = m.dim();
  VtuGrid grid;
  grid.points = state.positions;
  grid.cells.push_back({dim == 2 ? VtkCellType::kQuad : VtkCellType::kHexahedron, m.elements()});
  Eigen::MatrixXd u(m.num_nodes(), dim);
  for (int n = 0; n < m.num_nodes(); ++n) u.row(n) = state.displacement.segment(n * dim, dim).transpose();
  grid.point_data.push_back(DataArray::vectors("displacement", u));
  grid.point_data.push_back(DataArray::symmetric_tensors("stress", state.stress.nodal));
  grid.point_data.push_back(DataArray::scalars("von_mises", state.stress.nodal_von_mises));
  Eigen::VectorXi tags = Eigen::VectorXi::Zero(m.num_nodes());
  for (int n : m.bottom_nodes()) tags(n) |= kContactTag;
  for (const auto& d : body.definition().dirichlet)
    for (int n : m.face_nodes(d.face)) tags(n) |= kDirichletTag;
  for (const auto& t : body.definition().tractions)
    for (int n : m.face_nodes(t.face)) tags(n) |= kTractionTag;
  grid.point_data.push_back(DataArray::integers("boundary_tag", tags));
  grid.cell_data.push_back(DataArray::symmetric_tensors("stress", state.stress.element));
  grid.cell_data.push_back(DataArray::scalars("von_mises", state.stress.element_von_mises));
  return grid;
}

void write_state_vtu(const std::filesystem::path& path, const study::ElasticBody& body, const study::BodyState& state) {
  write_vtu(path, make_state_grid(body, state));
}

}  // namespace frictopt::io
