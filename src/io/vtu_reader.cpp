// SPDX-License-Identifier: MIT
#include "frictopt/io/vtu_reader.hpp"

#include <fmt/format.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <system_error>

#include "frictopt/core/error.hpp"
#include "vtk_error_capture.hpp"

namespace frictopt::io {
namespace {

std::vector<VtuArray> read_arrays(vtkFieldData* data) {
  std::vector<VtuArray> out;
  for (int i = 0; i < data->GetNumberOfArrays(); ++i) {
    vtkDataArray* array = data->GetArray(i);
    if (array == nullptr) continue;  // string or other non-numeric array
    VtuArray a;
    a.name = array->GetName() != nullptr ? array->GetName() : "";
    a.num_components = array->GetNumberOfComponents();
    a.is_integer = array->GetDataType() != VTK_FLOAT && array->GetDataType() != VTK_DOUBLE;
    a.values.resize(array->GetNumberOfTuples(), a.num_components);
    for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
      for (int c = 0; c < a.num_components; ++c) a.values(t, c) = array->GetComponent(t, c);
    out.push_back(std::move(a));
  }
  return out;
}

const VtuArray* find(const std::vector<VtuArray>& arrays, const std::string& name) {
  for (const VtuArray& a : arrays)
    if (a.name == name) return &a;
  return nullptr;
}

}  // namespace

const VtuArray* VtuContents::point_array(const std::string& name) const {
  return find(point_arrays, name);
}

const VtuArray* VtuContents::cell_array(const std::string& name) const {
  return find(cell_arrays, name);
}

VtuContents read_vtu_arrays(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InvalidInput(fmt::format("read_vtu_arrays: '{}' does not exist", path.string()));
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  detail::VtkErrorCapture capture(reader);
  if (reader->CanReadFile(path.c_str()) == 0)
    throw InvalidInput(
        fmt::format("read_vtu_arrays: '{}' is not a VTK XML unstructured grid", path.string()));
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  if (capture.has_error() || grid == nullptr)
    throw InvalidInput(
        fmt::format("read_vtu_arrays: could not read '{}': {}", path.string(), capture.errors()));

  VtuContents out;
  out.num_points = grid->GetNumberOfPoints();
  out.num_cells = grid->GetNumberOfCells();
  out.points.resize(out.num_points, 3);
  for (vtkIdType i = 0; i < out.num_points; ++i) {
    double x[3];
    grid->GetPoint(i, x);
    out.points.row(i) << x[0], x[1], x[2];
  }
  vtkNew<vtkIdList> ids;
  out.offsets.push_back(0);
  for (vtkIdType c = 0; c < out.num_cells; ++c) {
    out.cell_types.push_back(grid->GetCellType(c));
    grid->GetCellPoints(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) out.connectivity.push_back(ids->GetId(k));
    out.offsets.push_back(static_cast<std::int64_t>(out.connectivity.size()));
  }
  out.point_arrays = read_arrays(grid->GetPointData());
  out.cell_arrays = read_arrays(grid->GetCellData());
  return out;
}

}  // namespace frictopt::io
