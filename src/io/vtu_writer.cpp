// SPDX-License-Identifier: MIT
#include "frictopt/io/vtu_writer.hpp"

#include <fmt/format.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <set>
#include <system_error>

#include "atomic_file.hpp"
#include "frictopt/core/error.hpp"
#include "vtk_error_capture.hpp"

namespace frictopt::io {
namespace {

void check_array(const DataArray& array, Eigen::Index expected_rows, std::string_view kind,
                 std::set<std::string>& names) {
  if (array.name.empty())
    throw InvalidInput(fmt::format("write_vtu: a {} array has an empty name", kind));
  if (!names.insert(array.name).second)
    throw InvalidInput(fmt::format("write_vtu: {} array '{}' appears twice", kind, array.name));
  if (array.rows() != expected_rows)
    throw InvalidInput(fmt::format(
        "write_vtu: {} array '{}' has {} rows; expected {} (one per "
        "{})",
        kind, array.name, array.rows(), expected_rows, kind == "point" ? "point" : "cell"));
  if (array.num_components() < 1)
    throw InvalidInput(fmt::format("write_vtu: {} array '{}' has no components", kind, array.name));
  if (!array.component_names.empty() &&
      static_cast<Eigen::Index>(array.component_names.size()) != array.num_components())
    throw InvalidInput(
        fmt::format("write_vtu: {} array '{}' has {} component names for {} "
                    "components",
                    kind, array.name, array.component_names.size(), array.num_components()));
}

// Copies an Eigen matrix (rows = tuples) into a VTK array of the matching value type.
template <class VtkArray, class Matrix>
vtkNew<VtkArray> to_vtk(const DataArray& array, const Matrix& m) {
  vtkNew<VtkArray> out;
  out->SetName(array.name.c_str());
  out->SetNumberOfComponents(static_cast<int>(m.cols()));
  out->SetNumberOfTuples(m.rows());
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index c = 0; c < m.cols(); ++c)
      out->SetTypedComponent(i, static_cast<int>(c), m(i, c));
  for (std::size_t c = 0; c < array.component_names.size(); ++c)
    out->SetComponentName(static_cast<vtkIdType>(c), array.component_names[c].c_str());
  return out;
}

void add_arrays(const std::vector<DataArray>& arrays, vtkFieldData* target) {
  for (const DataArray& array : arrays) {
    if (const auto* real = std::get_if<Eigen::MatrixXd>(&array.values))
      target->AddArray(to_vtk<vtkDoubleArray>(array, *real));
    else
      target->AddArray(to_vtk<vtkIntArray>(array, std::get<Eigen::MatrixXi>(array.values)));
  }
}

}  // namespace

int num_cell_points(VtkCellType type) {
  switch (type) {
    case VtkCellType::kVertex:
      return 1;
    case VtkCellType::kLine:
      return 2;
    case VtkCellType::kTriangle:
      return 3;
    case VtkCellType::kQuad:
      return 4;
    case VtkCellType::kTetra:
      return 4;
    case VtkCellType::kHexahedron:
      return 8;
  }
  throw InvalidInput(fmt::format("unknown VTK cell type {}", static_cast<int>(type)));
}

DataArray DataArray::scalars(std::string name, const Eigen::VectorXd& values) {
  return DataArray{std::move(name), Eigen::MatrixXd(values), {}};
}

DataArray DataArray::vectors(std::string name, const Eigen::MatrixXd& values) {
  if (values.cols() != 2 && values.cols() != 3)
    throw InvalidInput(
        fmt::format("DataArray::vectors('{}'): {} columns; expected 2 or 3", name, values.cols()));
  Eigen::MatrixXd padded = Eigen::MatrixXd::Zero(values.rows(), 3);
  padded.leftCols(values.cols()) = values;
  return DataArray{std::move(name), std::move(padded), {}};
}

DataArray DataArray::symmetric_tensors(std::string name, const Eigen::MatrixXd& voigt) {
  if (voigt.cols() != 6)
    throw InvalidInput(
        fmt::format("DataArray::symmetric_tensors('{}'): {} columns; expected 6 "
                    "(XX, YY, ZZ, XY, YZ, XZ)",
                    name, voigt.cols()));
  // Full row-major tensor [XX XY XZ; XY YY YZ; XZ YZ ZZ] from (XX, YY, ZZ, XY, YZ, XZ).
  constexpr int kVoigtOfFull[9] = {0, 3, 5, 3, 1, 4, 5, 4, 2};
  Eigen::MatrixXd full(voigt.rows(), 9);
  for (int k = 0; k < 9; ++k) full.col(k) = voigt.col(kVoigtOfFull[k]);
  return DataArray{
      std::move(name), std::move(full), {"XX", "XY", "XZ", "YX", "YY", "YZ", "ZX", "ZY", "ZZ"}};
}

DataArray DataArray::integers(std::string name, const Eigen::VectorXi& values) {
  return DataArray{std::move(name), Eigen::MatrixXi(values), {}};
}

Eigen::Index DataArray::rows() const {
  return std::visit([](const auto& m) { return m.rows(); }, values);
}

Eigen::Index DataArray::num_components() const {
  return std::visit([](const auto& m) { return m.cols(); }, values);
}

void write_vtu(const std::filesystem::path& path, const VtuGrid& grid) {
  const Eigen::Index n_points = grid.points.rows();
  if (grid.points.cols() != 2 && grid.points.cols() != 3)
    throw InvalidInput(fmt::format("write_vtu({}): points have {} columns; expected 2 or 3",
                                   path.string(), grid.points.cols()));
  if (!grid.points.allFinite())
    throw InvalidInput(
        fmt::format("write_vtu({}): a point coordinate is not finite", path.string()));

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n_points);
  for (Eigen::Index i = 0; i < n_points; ++i)
    points->SetPoint(i, grid.points(i, 0), grid.points(i, 1),
                     grid.points.cols() == 3 ? grid.points(i, 2) : 0.0);

  Eigen::Index n_cells = 0;
  Eigen::Index n_connectivity = 0;
  for (const CellBlock& block : grid.cells) {
    n_cells += block.connectivity.rows();
    n_connectivity += block.connectivity.size();
  }
  vtkNew<vtkCellArray> cells;
  cells->AllocateExact(n_cells, n_connectivity);
  vtkNew<vtkUnsignedCharArray> types;
  types->SetNumberOfTuples(n_cells);
  Eigen::Index cell = 0;
  std::vector<vtkIdType> ids;
  for (std::size_t b = 0; b < grid.cells.size(); ++b) {
    const CellBlock& block = grid.cells[b];
    const int width = num_cell_points(block.type);
    if (block.connectivity.rows() > 0 && block.connectivity.cols() != width)
      throw InvalidInput(fmt::format(
          "write_vtu({}): cell block {} has {} points per cell; "
          "expected {} for VTK cell type {}",
          path.string(), b, block.connectivity.cols(), width, static_cast<int>(block.type)));
    ids.resize(static_cast<std::size_t>(width));
    for (Eigen::Index i = 0; i < block.connectivity.rows(); ++i, ++cell) {
      for (int k = 0; k < width; ++k) {
        const int id = block.connectivity(i, k);
        if (id < 0 || id >= n_points)
          throw InvalidInput(
              fmt::format("write_vtu({}): cell {} of block {} refers to point {}; "
                          "expected 0 <= index < {}",
                          path.string(), i, b, id, n_points));
        ids[static_cast<std::size_t>(k)] = id;
      }
      cells->InsertNextCell(width, ids.data());
      types->SetValue(cell, static_cast<unsigned char>(block.type));
    }
  }

  std::set<std::string> point_names;
  std::set<std::string> cell_names;
  for (const DataArray& a : grid.point_data) check_array(a, n_points, "point", point_names);
  for (const DataArray& a : grid.cell_data) check_array(a, n_cells, "cell", cell_names);

  vtkNew<vtkUnstructuredGrid> ugrid;
  ugrid->SetPoints(points);
  ugrid->SetCells(types, cells);
  add_arrays(grid.point_data, ugrid->GetPointData());
  add_arrays(grid.cell_data, ugrid->GetCellData());

  // VTK reports a missing directory only as a generic "cannot open file"; say which part.
  const std::filesystem::path parent = path.parent_path();
  std::error_code ec;
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
    throw InvalidInput(fmt::format("write_vtu: directory '{}' does not exist", parent.string()));

  // VTK writes into a string, and frictopt's own writer puts it on disk (atomic_file.hpp): VTK's
  // file stream does not report a write that fails at its final flush (a full disk gave a
  // truncated file and no error), while write_file_atomically checks every write and the close
  // and replaces the target only with the complete file.
  detail::require_regular_output(path);
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  detail::VtkErrorCapture capture(writer);
  writer->WriteToOutputStringOn();
  writer->SetInputData(ugrid);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary: smaller and faster than base64
  writer->SetCompressorTypeToZLib();
  // 64-bit headers so files above 4 GiB (large 3D series) stay valid.
  writer->SetHeaderTypeToUInt64();
  if (writer->Write() != 1 || capture.has_error() || writer->GetErrorCode() != 0)
    throw InvalidInput(fmt::format("write_vtu: could not write '{}': {}", path.string(),
                                   capture.has_error() ? capture.errors() : "unknown VTK error"));
  const std::string xml = writer->GetOutputString();
  detail::write_file_atomically(path, xml);
}

}  // namespace frictopt::io
