// SPDX-License-Identifier: MIT
#include "frictopt/io/state_output.hpp"

#include "frictopt/io/csv_writer.hpp"

#include <limits>
#include <map>

namespace frictopt::io {

Eigen::VectorXd contact_tributary_areas(const study::ElasticBody& body) {
  return body.contact_boundary()->tributary_areas();
}

void add_contact_fields(VtuGrid& grid, const study::ElasticBody& body, const study::ContactResult& result) {
  const mesh::Mesh& m = body.mesh();
  const contact::ContactBoundary& boundary = *body.contact_boundary();
  const int dim = m.dim();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Eigen::VectorXd area = contact_tributary_areas(body);
  Eigen::VectorXd pressure = Eigen::VectorXd::Constant(m.num_nodes(), nan);
  Eigen::VectorXd gap = Eigen::VectorXd::Constant(m.num_nodes(), nan);
  Eigen::MatrixXd traction = Eigen::MatrixXd::Constant(m.num_nodes(), 3, nan);
  Eigen::MatrixXd slip = Eigen::MatrixXd::Constant(m.num_nodes(), 3, nan);
  Eigen::VectorXi status = Eigen::VectorXi::Constant(m.num_nodes(), -1);
  const contact::ContactState& cs = result.state;
  for (Eigen::Index i = 0; i < boundary.num_nodes(); ++i) {
    const int n = boundary.nodes()[static_cast<std::size_t>(i)];
    pressure(n) = cs.lambda(i) / area(i);
    gap(n) = cs.normal_gap(i);
    traction.row(n).setZero();
    slip.row(n).setZero();
    // In global axes: component c of the frame's tangent t_c carries τ_c and u_t,c (the
    // standard foundation: t_c = e_c).
    const Eigen::MatrixXd& tangents = boundary.foundation().frame.tangents;
    for (int c = 0; c < dim - 1; ++c)
      for (int k = 0; k < dim; ++k) {
        traction(n, k) += tangents(k, c) * (-cs.z(dim * i + c) / area(i));  // τ = −q: the traction the foundation exerts
        slip(n, k) += tangents(k, c) * (-cs.gradient(dim * i + c));          // ∇_q K = −u_t
      }
    status(n) = static_cast<int>(cs.nodes[static_cast<std::size_t>(i)].status);
  }
  grid.point_data.push_back(DataArray::scalars("contact_pressure", pressure));
  grid.point_data.push_back(DataArray::vectors("contact_traction", traction));
  grid.point_data.push_back(DataArray::vectors("slip", slip));
  grid.point_data.push_back(DataArray::scalars("contact_gap", gap));
  grid.point_data.push_back(DataArray::integers("contact_status", status));
}

VtuGrid make_state_grid(const study::ElasticBody& body, const study::BodyState& state) {
  const mesh::Mesh& m = body.mesh();
  const int dim = m.dim();
  VtuGrid grid;
  grid.points = state.positions;
  grid.cells.push_back({static_cast<VtkCellType>(m.vtk_cell_type()), m.elements()});
  Eigen::MatrixXd u(m.num_nodes(), dim);
  for (int n = 0; n < m.num_nodes(); ++n)
    u.row(n) = state.displacement.segment(n * dim, dim).transpose();
  grid.point_data.push_back(DataArray::vectors("displacement", u));
  grid.point_data.push_back(DataArray::symmetric_tensors("stress", state.stress.nodal));
  grid.point_data.push_back(DataArray::scalars("von_mises", state.stress.nodal_von_mises));
  Eigen::VectorXi tags = Eigen::VectorXi::Zero(m.num_nodes());
  for (int n : m.boundary(body.contact_surface()).nodes) tags(n) |= kContactTag;
  for (const auto& d : body.definition().dirichlet)
    for (int n : m.boundary(d.boundary).nodes) tags(n) |= kDirichletTag;
  for (const auto& t : body.definition().tractions)
    for (int n : m.boundary(t.boundary).nodes) tags(n) |= kTractionTag;
  grid.point_data.push_back(DataArray::integers("boundary_tag", tags));
  if (state.contact && body.contact_boundary()) add_contact_fields(grid, body, *state.contact);
  grid.cell_data.push_back(DataArray::symmetric_tensors("stress", state.stress.element));
  grid.cell_data.push_back(DataArray::scalars("von_mises", state.stress.element_von_mises));
  return grid;
}

void write_state_vtu(const std::filesystem::path& path, const study::ElasticBody& body,
                     const study::BodyState& state) {
  write_vtu(path, make_state_grid(body, state));
}

}  // namespace frictopt::io

namespace frictopt::io {

void write_contact_csv(const std::filesystem::path& path, const study::ElasticBody& body,
                       const study::ContactResult& result) {
  const contact::ContactBoundary& boundary = *body.contact_boundary();
  const Eigen::VectorXd area = contact_tributary_areas(body);
  const contact::ContactState& cs = result.state;
  CsvWriter csv(path, {"x1", "initial_gap", "normal_force", "pressure", "tangential_force", "tangential_traction",
                       "tangential_displacement", "gap_after_deformation", "status"},
                CsvWriter::Mode::kReplace);
  for (Eigen::Index i = 0; i < boundary.num_nodes(); ++i) {
    const double tau = -cs.z(2 * i);
    csv.write_row({boundary.plane_coordinates()(i, 0), result.gaps(i), cs.lambda(i), cs.lambda(i) / area(i), tau,
                   tau / area(i), -cs.gradient(2 * i), cs.normal_gap(i),
                   std::string(contact::to_string(cs.nodes[static_cast<std::size_t>(i)].status))});
  }
  csv.finish();
}

}  // namespace frictopt::io
