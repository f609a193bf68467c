// SPDX-License-Identifier: MIT
// Reading back a .vtu file's points, cells and data arrays, for tests and CLI checks that a
// written file carries what it should. Not a general mesh importer.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace frictopt::io {

/// One data array as read back: values as doubles (integers converted exactly up to 2^53).
struct VtuArray {
  std::string name;
  int num_components = 0;
  Eigen::MatrixXd values;   ///< n_points (or n_cells) × num_components
  bool is_integer = false;  ///< stored as an integer type in the file
};

/// What read_vtu_arrays found in a .vtu file.
struct VtuContents {
  Eigen::Index num_points = 0;
  Eigen::Index num_cells = 0;
  Eigen::MatrixXd points;       ///< num_points × 3
  std::vector<int> cell_types;  ///< VTK cell type id per cell
  std::vector<std::int64_t>
      offsets;  ///< num_cells + 1; cell i is connectivity[offsets[i]..offsets[i+1])
  std::vector<std::int64_t> connectivity;
  std::vector<VtuArray> point_arrays;  ///< in file order
  std::vector<VtuArray> cell_arrays;   ///< in file order

  /// The point (cell) array called `name`, or null.
  [[nodiscard]] const VtuArray* point_array(const std::string& name) const;
  [[nodiscard]] const VtuArray* cell_array(const std::string& name) const;
};

/// Reads `path` with vtkXMLUnstructuredGridReader. Throws InvalidInput naming the path if the
/// file is missing or is not a readable .vtu file.
[[nodiscard]] VtuContents read_vtu_arrays(const std::filesystem::path& path);

}  // namespace frictopt::io
