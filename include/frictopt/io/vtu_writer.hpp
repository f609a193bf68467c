// SPDX-License-Identifier: MIT
// A generic VTK XML unstructured-grid (.vtu) writer: points, cells and named point/cell data,
// as plain Eigen data. It knows nothing about meshes or solvers; the caller (study, apps)
// fills a VtuGrid from whatever it has. VTK itself stays inside src/io.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

namespace frictopt::io {

/// VTK cell type ids (vtkCellType.h); the values are VTK's, so they can be compared with
/// what other VTK tools report.
enum class VtkCellType : std::uint8_t {
  kVertex = 1,
  kLine = 3,
  kTriangle = 5,
  kQuad = 9,
  kTetra = 10,
  kHexahedron = 12
};

/// Number of points of a cell of `type` (1, 2, 3, 4, 4, 8).
[[nodiscard]] int num_cell_points(VtkCellType type);

/// Cells of one type. `connectivity` is n_cells × num_cell_points(type), zero-based point
/// indices in VTK's node order (VTK_QUAD counter-clockwise; VTK_HEXAHEDRON bottom face
/// counter-clockwise seen from above, then the top face in the same order).
struct CellBlock {
  VtkCellType type = VtkCellType::kQuad;
  Eigen::MatrixXi connectivity;
};

/// A named array of point or cell data: one row per point (cell), one column per component.
/// Real values are written as Float64, integer values (tags, statuses) as Int32.
struct DataArray {
  std::string name;
  std::variant<Eigen::MatrixXd, Eigen::MatrixXi> values;
  /// Optional component names (e.g. "XX", "XY"); empty, or one per column.
  std::vector<std::string> component_names;

  /// One component per row.
  [[nodiscard]] static DataArray scalars(std::string name, const Eigen::VectorXd& values);
  /// An n × 2 or n × 3 vector field, padded to 3 components (VTK filters such as warping
  /// expect 3-component vectors, also in 2D).
  [[nodiscard]] static DataArray vectors(std::string name, const Eigen::MatrixXd& values);
  /// A symmetric tensor per row, given as n × 6 in the order XX, YY, ZZ, XY, YZ, XZ (ParaView's
  /// order for symmetric tensors), written as 9 components (row-major full tensor), which
  /// every VTK reader treats as a tensor. In 2D pass ZZ (plane strain) or 0 and YZ = XZ = 0.
  [[nodiscard]] static DataArray symmetric_tensors(std::string name, const Eigen::MatrixXd& voigt);
  /// Integer tags, one per row.
  [[nodiscard]] static DataArray integers(std::string name, const Eigen::VectorXi& values);

  [[nodiscard]] Eigen::Index rows() const;
  [[nodiscard]] Eigen::Index num_components() const;
};

/// An unstructured grid to write.
struct VtuGrid {
  /// n_points × 2 or n_points × 3 coordinates [m]; 2D points get z = 0.
  Eigen::MatrixXd points;
  /// Cells, possibly of several types; cell i of the file is the i-th cell in block order.
  std::vector<CellBlock> cells;
  std::vector<DataArray> point_data;  ///< each with points.rows() rows
  std::vector<DataArray> cell_data;   ///< each with as many rows as there are cells
};

/// Writes `grid` to `path` as a VTK XML unstructured grid (.vtu) with vtkXMLUnstructuredGridWriter:
/// binary appended data, zlib-compressed. Overwrites an existing file; the parent directory
/// must exist.
///
/// Throws InvalidInput, naming the offending item, if the points are not n × 2 or n × 3, a
/// connectivity index is out of range or has the wrong width for its cell type, an array has
/// the wrong number of rows, two arrays of one kind share a name or have an empty name, a
/// point coordinate is not finite, or the file cannot be written (the path is user input
/// from the CLI, hence InvalidInput). Data values may be NaN (e.g. a contact pressure at
/// nodes off Γ_c): VTK and ParaView show NaN as "no value".
void write_vtu(const std::filesystem::path& path, const VtuGrid& grid);

}  // namespace frictopt::io
