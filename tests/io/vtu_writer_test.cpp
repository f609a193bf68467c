// SPDX-License-Identifier: MIT
// VTU output: a grid written with write_vtu reads back (through VTK's own reader) with the
// same points, cells, array names, component counts and values; bad grids are rejected.
#include "frictopt/io/vtu_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "common/temporary_directory.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/vtu_reader.hpp"

namespace frictopt::io {
namespace {

namespace fs = std::filesystem;

class VtuFiles : public frictopt::testing::TemporaryDirectoryTest {};

// Two unit hexahedra side by side along x1: 3×2×2 = 12 points, VTK node order.
VtuGrid two_hexahedra() {
  VtuGrid grid;
  grid.points.resize(12, 3);
  int p = 0;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) grid.points.row(p++) << i, j, k;
  const auto id = [](int i, int j, int k) { return i + 3 * j + 6 * k; };
  CellBlock hexes{VtkCellType::kHexahedron, Eigen::MatrixXi(2, 8)};
  for (int e = 0; e < 2; ++e)
    hexes.connectivity.row(e) << id(e, 0, 0), id(e + 1, 0, 0), id(e + 1, 1, 0), id(e, 1, 0),
        id(e, 0, 1), id(e + 1, 0, 1), id(e + 1, 1, 1), id(e, 1, 1);
  grid.cells.push_back(hexes);

  Eigen::MatrixXd u(12, 3);
  Eigen::VectorXd von_mises(12);
  for (int i = 0; i < 12; ++i) {
    const Eigen::Vector3d x = grid.points.row(i);
    u.row(i) << 1e-3 * x.z(), 0.0, -1e-3 * x.x() / 3.0;  // arbitrary, distinct per point
    von_mises(i) = 1e6 * (1.0 + x.x() + 0.1 * x.y() + 0.01 * x.z()) / 3.0;
  }
  grid.point_data.push_back(DataArray::vectors("displacement", u));
  grid.point_data.push_back(DataArray::scalars("von_mises", von_mises));
  Eigen::MatrixXd stress(2, 6);
  stress << 1, 2, 3, 4, 5, 6, -1, -2, -3, -4, -5, -6;
  grid.cell_data.push_back(DataArray::symmetric_tensors("stress", stress));
  grid.cell_data.push_back(DataArray::integers("material_tag", Eigen::Vector2i(7, -3)));
  return grid;
}

// The file stores Float64 values in binary and compresses them losslessly (zlib), so every
// value must come back bit for bit: the comparisons below are exact on purpose.
TEST_F(VtuFiles, HexahedralGridRoundTripsExactly) {
  const VtuGrid grid = two_hexahedra();
  const fs::path file = dir_ / "block.vtu";
  write_vtu(file, grid);
  const VtuContents back = read_vtu_arrays(file);

  EXPECT_EQ(back.num_points, 12);
  EXPECT_EQ(back.num_cells, 2);
  EXPECT_EQ(back.points, grid.points);
  EXPECT_EQ(back.cell_types, (std::vector<int>{12, 12}));
  ASSERT_EQ(back.offsets, (std::vector<std::int64_t>{0, 8, 16}));
  for (int e = 0; e < 2; ++e)
    for (int k = 0; k < 8; ++k)
      EXPECT_EQ(back.connectivity[8 * e + k], grid.cells[0].connectivity(e, k));

  ASSERT_EQ(back.point_arrays.size(), 2u);
  EXPECT_EQ(back.point_arrays[0].name, "displacement");
  EXPECT_EQ(back.point_arrays[0].num_components, 3);
  EXPECT_EQ(back.point_arrays[0].values, std::get<Eigen::MatrixXd>(grid.point_data[0].values));
  EXPECT_FALSE(back.point_arrays[0].is_integer);
  const VtuArray* vm = back.point_array("von_mises");
  ASSERT_NE(vm, nullptr);
  EXPECT_EQ(vm->num_components, 1);
  EXPECT_EQ(vm->values, std::get<Eigen::MatrixXd>(grid.point_data[1].values));

  const VtuArray* stress = back.cell_array("stress");
  ASSERT_NE(stress, nullptr);
  ASSERT_EQ(stress->num_components, 9);
  // Row-major full tensor [XX XY XZ; YX YY YZ; ZX ZY ZZ] from (XX, YY, ZZ, XY, YZ, XZ).
  Eigen::RowVectorXd expected(9);
  expected << 1, 4, 6, 4, 2, 5, 6, 5, 3;
  EXPECT_EQ(stress->values.row(0), expected);
  EXPECT_EQ(stress->values.row(1), -expected);
  const VtuArray* tag = back.cell_array("material_tag");
  ASSERT_NE(tag, nullptr);
  EXPECT_TRUE(tag->is_integer);
  EXPECT_EQ(tag->values(0, 0), 7);
  EXPECT_EQ(tag->values(1, 0), -3);
}

TEST_F(VtuFiles, PlanarGridIsPaddedToZeroZAndThreeComponentVectors) {
  VtuGrid grid;
  grid.points.resize(4, 2);
  grid.points << 0, 0, 1, 0, 1, 1, 0, 1;
  grid.cells.push_back({VtkCellType::kQuad, Eigen::RowVector4i(0, 1, 2, 3)});
  grid.cells.push_back({VtkCellType::kLine, Eigen::RowVector2i(0, 1)});
  Eigen::MatrixXd u(4, 2);
  u << 0, 0, 1, 2, 3, 4, 5, 6;
  grid.point_data.push_back(DataArray::vectors("displacement", u));
  Eigen::VectorXd pressure(4);
  pressure << 1.0, 2.0, std::numeric_limits<double>::quiet_NaN(), 0.5;
  grid.point_data.push_back(DataArray::scalars("contact_pressure", pressure));
  const fs::path file = dir_ / "plate.vtu";
  write_vtu(file, grid);

  const VtuContents back = read_vtu_arrays(file);
  EXPECT_EQ(back.cell_types, (std::vector<int>{9, 3}));
  EXPECT_EQ(back.points.col(2), Eigen::VectorXd::Zero(4));
  const VtuArray* d = back.point_array("displacement");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->num_components, 3);
  EXPECT_EQ(d->values.leftCols(2), u);
  EXPECT_EQ(d->values.col(2), Eigen::VectorXd::Zero(4));
  EXPECT_TRUE(std::isnan(back.point_array("contact_pressure")->values(2, 0)))
      << "NaN marks nodes without a value and must survive";
}

TEST_F(VtuFiles, InconsistentGridsAreRejectedWithTheReason) {
  const fs::path file = dir_ / "bad.vtu";
  const auto expect_message = [&](const VtuGrid& grid, const std::string& fragment) {
    try {
      write_vtu(file, grid);
      ADD_FAILURE() << "no InvalidInput; expected '" << fragment << "'";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  VtuGrid out_of_range = two_hexahedra();
  out_of_range.cells[0].connectivity(1, 6) = 12;
  expect_message(out_of_range, "cell 1 of block 0 refers to point 12");

  VtuGrid wrong_width = two_hexahedra();
  wrong_width.cells[0].type = VtkCellType::kQuad;
  expect_message(wrong_width, "8 points per cell; expected 4");

  VtuGrid wrong_rows = two_hexahedra();
  wrong_rows.point_data.push_back(DataArray::scalars("short", Eigen::VectorXd::Zero(11)));
  expect_message(wrong_rows, "point array 'short' has 11 rows; expected 12");

  VtuGrid duplicate = two_hexahedra();
  duplicate.cell_data.push_back(DataArray::integers("material_tag", Eigen::Vector2i(0, 0)));
  expect_message(duplicate, "cell array 'material_tag' appears twice");

  VtuGrid bad_points = two_hexahedra();
  bad_points.points(3, 1) = std::numeric_limits<double>::infinity();
  expect_message(bad_points, "not finite");
}

TEST_F(VtuFiles, MissingDirectoryIsNamed) {
  try {
    write_vtu(dir_ / "no" / "such" / "x.vtu", two_hexahedra());
    ADD_FAILURE() << "no InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
}

TEST_F(VtuFiles, ReadingAFileThatIsNotAVtuIsInvalidInput) {
  EXPECT_THROW((void)read_vtu_arrays(dir_ / "absent.vtu"), InvalidInput);
  { std::ofstream(dir_ / "text.vtu") << "not xml at all\n"; }
  EXPECT_THROW((void)read_vtu_arrays(dir_ / "text.vtu"), InvalidInput);
}

TEST(DataArray, VectorsRejectAWrongNumberOfColumns) {
  EXPECT_THROW((void)DataArray::vectors("u", Eigen::MatrixXd::Zero(3, 4)), InvalidInput);
  EXPECT_THROW((void)DataArray::symmetric_tensors("s", Eigen::MatrixXd::Zero(3, 3)), InvalidInput);
}

}  // namespace
}  // namespace frictopt::io
