// SPDX-License-Identifier: MIT
// Writes two synthetic result files, a 3D block and a 2D plate with a curved (paraboloid)
// bottom, carrying the arrays the solvers will write: displacement, von_mises, stress,
// contact_pressure and contact_status (NaN / -1 off Γ_c). The fields are analytic stand-ins
// with the right shape (a Hertz-like pressure patch, a stick core inside a slip ring), not
// solutions; they let the viz scripts be tested before the solvers exist.
//
//   write_sample_vtu OUT_DIR   -> OUT_DIR/block3d.vtu, OUT_DIR/plate2d.vtu
#include <Eigen/Core>
#include <cmath>
#include <exception>
#include <filesystem>
#include <iostream>
#include <limits>

#include "frictopt/io/vtu_writer.hpp"

namespace {

using frictopt::io::CellBlock;
using frictopt::io::DataArray;
using frictopt::io::VtkCellType;
using frictopt::io::VtuGrid;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPeakPressure = 2.0e7;  // Pa
constexpr double kIndentation = 0.01;    // m, downward motion of the top

// Contact status codes used by the viz scripts (docs/case-format.md, "Output arrays").
constexpr int kOffContact = -1;
constexpr int kSeparated = 0;
constexpr int kStick = 1;
constexpr int kSlip = 2;

// Paraboloid bottom G (0 at the centre, 0.1 at the corners) over (0,a)×(0,b).
double bottom(double x, double y, double a, double b) {
  const double rx = (x - a / 2) / (a / 2);
  const double ry = b > 0 ? (y - b / 2) / (b / 2) : 0.0;
  return 0.05 * (rx * rx + ry * ry);
}

struct Fields {
  Eigen::MatrixXd u;
  Eigen::VectorXd von_mises, pressure;
  Eigen::VectorXi status;
};

// Fields at a node with reference height fraction s (0 = bottom) and normalized contact
// radius r (0 at the centre of the patch, 1 at its rim).
void fill_node(Fields& f, int i, int dim, double s, double r, double depth) {
  f.u.row(i).setZero();
  f.u(i, 0) = 0.3 * kIndentation * s * s;  // a little shear toward +x1
  f.u(i, dim - 1) = -kIndentation * s;     // the top moves down, the patch stays
  f.von_mises(i) = kPeakPressure * (0.15 + 0.85 * std::exp(-(r * r + 4 * depth * depth)));
  if (s > 0) {
    f.pressure(i) = kNaN;
    f.status(i) = kOffContact;
  } else if (r < 1) {
    f.pressure(i) = kPeakPressure * std::sqrt(1 - r * r);
    f.status(i) = r < 0.6 ? kStick : kSlip;
  } else {
    f.pressure(i) = 0;
    f.status(i) = kSeparated;
  }
}

VtuGrid finish(VtuGrid grid, const Fields& f) {
  grid.point_data.push_back(DataArray::vectors("displacement", f.u));
  grid.point_data.push_back(DataArray::scalars("von_mises", f.von_mises));
  grid.point_data.push_back(DataArray::scalars("contact_pressure", f.pressure));
  grid.point_data.push_back(DataArray::integers("contact_status", f.status));
  return grid;
}

VtuGrid block3d() {
  const double a = 2, b = 1, h = 1;
  const int n1 = 24, n2 = 12, n3 = 8;
  const auto id = [&](int i, int j, int k) { return i + (n1 + 1) * (j + (n2 + 1) * k); };
  const int n_points = (n1 + 1) * (n2 + 1) * (n3 + 1);
  VtuGrid grid;
  grid.points.resize(n_points, 3);
  Fields f{Eigen::MatrixXd(n_points, 3), Eigen::VectorXd(n_points), Eigen::VectorXd(n_points),
           Eigen::VectorXi(n_points)};
  for (int k = 0; k <= n3; ++k)
    for (int j = 0; j <= n2; ++j)
      for (int i = 0; i <= n1; ++i) {
        const double x = a * i / n1, y = b * j / n2, s = double(k) / n3;
        const double g = bottom(x, y, a, b);
        const double z = g + s * (h - g);
        grid.points.row(id(i, j, k)) << x, y, z;
        // Elliptic patch with semi-axes 0.5 (x1) and 0.3 (x2).
        const double r = std::hypot((x - a / 2) / 0.5, (y - b / 2) / 0.3);
        fill_node(f, id(i, j, k), 3, s, r, z);
      }
  CellBlock hexes{VtkCellType::kHexahedron, Eigen::MatrixXi(n1 * n2 * n3, 8)};
  int e = 0;
  for (int k = 0; k < n3; ++k)
    for (int j = 0; j < n2; ++j)
      for (int i = 0; i < n1; ++i)
        hexes.connectivity.row(e++) << id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k),
            id(i, j + 1, k), id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1),
            id(i, j + 1, k + 1);
  grid.cells.push_back(hexes);
  return finish(std::move(grid), f);
}

VtuGrid plate2d() {
  const double a = 2, h = 1;
  const int n1 = 40, n2 = 12;
  const auto id = [&](int i, int k) { return i + (n1 + 1) * k; };
  const int n_points = (n1 + 1) * (n2 + 1);
  VtuGrid grid;
  grid.points.resize(n_points, 2);
  Fields f{Eigen::MatrixXd(n_points, 2), Eigen::VectorXd(n_points), Eigen::VectorXd(n_points),
           Eigen::VectorXi(n_points)};
  for (int k = 0; k <= n2; ++k)
    for (int i = 0; i <= n1; ++i) {
      const double x = a * i / n1, s = double(k) / n2;
      const double g = bottom(x, 0, a, 0);
      const double y = g + s * (h - g);
      grid.points.row(id(i, k)) << x, y;
      fill_node(f, id(i, k), 2, s, std::abs(x - a / 2) / 0.6, y);
    }
  CellBlock quads{VtkCellType::kQuad, Eigen::MatrixXi(n1 * n2, 4)};
  int e = 0;
  for (int k = 0; k < n2; ++k)
    for (int i = 0; i < n1; ++i)
      quads.connectivity.row(e++) << id(i, k), id(i + 1, k), id(i + 1, k + 1), id(i, k + 1);
  grid.cells.push_back(quads);
  return finish(std::move(grid), f);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: write_sample_vtu OUT_DIR\n";
    return 2;
  }
  try {
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    frictopt::io::write_vtu(dir / "block3d.vtu", block3d());
    frictopt::io::write_vtu(dir / "plate2d.vtu", plate2d());
  } catch (const std::exception& e) {
    std::cerr << "write_sample_vtu: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
