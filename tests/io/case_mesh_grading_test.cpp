// SPDX-License-Identifier: MIT
// The grading keys of [mesh] (docs/case-format.md, "[mesh]"): growth and refine_box (in-plane),
// vertical_grading, fine_depth and vertical_growth; their defaults, and the messages naming
// the field.
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <string_view>

#include "common/invalid_case.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/mesh/grid_resolution.hpp"

namespace frictopt::io {
namespace {

using testing::expect_invalid_case;
std::string case_text(int dim, std::string_view mesh_keys) {
  const std::string geometry = dim == 2 ? "dim = 2\na = 2.0\nheight = 1.0\n" : "dim = 3\na = 2.0\nb = 1.0\nheight = 1.0\n";
  const std::string cells = dim == 2 ? "cells = [30, 8]\n" : "cells = [30, 15, 8]\n";
  const std::string controls = dim == 2 ? "control_points = [4]\n" : "control_points = [3, 3]\n";
  return "[geometry]\n" + geometry + "\n[mesh]\n" + cells + std::string(mesh_keys) +
         "\n[material]\nyoung = 1e9\npoisson = 0.3\n\n[[dirichlet]]\nface = \"top\"\n\n[design]\n" + controls +
         "initial = 0.05\nupper_bound = 0.5\n";
}


TEST(CaseMeshGrading, DefaultIsUniformColumns) {
  const CaseDescription c = parse_case(case_text(3, ""), "case.toml");
  EXPECT_EQ(c.body.resolution.growth, 1.0);
  EXPECT_FALSE(c.body.resolution.refine_box.has_value());
}

TEST(CaseMeshGrading, ReadsGrowthAndTheBoxIn2DAnd3D) {
  const CaseDescription c2 = parse_case(case_text(2, "growth = 1.2\nrefine_box = [0.8, 1.2]\n"), "case.toml");
  EXPECT_EQ(c2.body.resolution.growth, 1.2);
  ASSERT_TRUE(c2.body.resolution.refine_box.has_value());
  EXPECT_EQ(*c2.body.resolution.refine_box, (std::array<double, 4>{0.8, 1.2, 0.0, 0.0}));
  const CaseDescription c3 =
      parse_case(case_text(3, "growth = 1.25\nrefine_box = [0.5, 1.5, 0.25, 0.75]\n"), "case.toml");
  EXPECT_EQ(*c3.body.resolution.refine_box, (std::array<double, 4>{0.5, 1.5, 0.25, 0.75}));
  // growth alone: the default box (the central third), no box stored.
  const CaseDescription d = parse_case(case_text(3, "growth = 1.2\n"), "case.toml");
  EXPECT_EQ(d.body.resolution.growth, 1.2);
  EXPECT_FALSE(d.body.resolution.refine_box.has_value());
}

TEST(CaseMeshGrading, BadValuesAreReportedWithTheField) {
  expect_invalid_case(case_text(2, "growth = 2.5\n"), {"mesh.growth = 2.5", "1 <= growth <= 2"});
  expect_invalid_case(case_text(2, "growth = 0.9\n"), {"mesh.growth = 0.9"});
  expect_invalid_case(case_text(2, "refine_box = [0.8, 1.2]\n"), {"mesh.refine_box", "growth = 1", "(1, 2]"});
  expect_invalid_case(case_text(2, "growth = 1.2\nrefine_box = [0.8, 1.2, 0.1, 0.2]\n"),
                 {"mesh.refine_box", "a list of 2 numbers [x1min, x1max]"});
  expect_invalid_case(case_text(3, "growth = 1.2\nrefine_box = [0.8, 1.2]\n"),
                 {"mesh.refine_box", "a list of 4 numbers"});
  expect_invalid_case(case_text(3, "growth = 1.2\nrefine_box = [0.5, 1.5, 0.25, 1.75]\n"),
                 {"mesh.refine_box[3] = 1.75", "[0, 1] m (geometry.b)"});
  expect_invalid_case(case_text(2, "growth = 1.2\nrefine_box = [1.2, 0.8]\n"),
                 {"mesh.refine_box[1] = 0.8", "a maximum > the minimum 1.2"});
  expect_invalid_case(case_text(2, "growth = 1.2\nrefine_box = [0.8, \"x\"]\n"), {"mesh.refine_box"});
  // Too few cells for the box and the sides at this growth: the message names the cell count.
  expect_invalid_case(case_text(2, "growth = 1.01\nrefine_box = [0.95, 1.05]\n"), {"mesh.cells[0] = 30", "growth = 1.01"});
  expect_invalid_case(case_text(2, "growth = 1.2\nrefin_box = [0.8, 1.2]\n"), {"refin_box", "refine_box"});
}

TEST(CaseMeshVerticalGrading, DefaultIsThePowerLaw) {
  const CaseDescription c = parse_case(case_text(3, "grading = 2\n"), "case.toml");
  EXPECT_EQ(c.body.resolution.vertical_grading, mesh::VerticalGrading::kPower);
  EXPECT_EQ(c.body.resolution.grading, 2.0);
  const CaseDescription p = parse_case(case_text(2, "vertical_grading = \"power\"\n"), "case.toml");
  EXPECT_EQ(p.body.resolution.vertical_grading, mesh::VerticalGrading::kPower);
}

TEST(CaseMeshVerticalGrading, ReadsContactWithFineDepthAndGrowthIn2DAnd3D) {
  const CaseDescription c2 =
      parse_case(case_text(2, "vertical_grading = \"contact\"\nfine_depth = 0.3\n"), "case.toml");
  EXPECT_EQ(c2.body.resolution.vertical_grading, mesh::VerticalGrading::kContact);
  EXPECT_EQ(c2.body.resolution.fine_depth, 0.3);
  EXPECT_EQ(c2.body.resolution.vertical_growth, 1.2);  // the default
  const CaseDescription c3 = parse_case(
      case_text(3, "growth = 1.2\nvertical_grading = \"contact\"\nfine_depth = 0.25\nvertical_growth = 1.5\n"),
      "case.toml");
  EXPECT_EQ(c3.body.resolution.vertical_grading, mesh::VerticalGrading::kContact);
  EXPECT_EQ(c3.body.resolution.fine_depth, 0.25);
  EXPECT_EQ(c3.body.resolution.vertical_growth, 1.5);
  EXPECT_EQ(c3.body.resolution.growth, 1.2);
}

TEST(CaseMeshVerticalGrading, BadValuesAreReportedWithTheField) {
  expect_invalid_case(case_text(2, "vertical_grading = \"geometric\"\n"),
                      {"mesh.vertical_grading", "\"power\", \"contact\""});
  expect_invalid_case(case_text(2, "vertical_grading = \"contact\"\n"), {"mesh.fine_depth", "missing"});
  expect_invalid_case(case_text(2, "vertical_grading = \"contact\"\nfine_depth = 1.0\n"),
                      {"mesh.fine_depth = 1", "(0, geometry.height = 1) m"});
  expect_invalid_case(case_text(2, "vertical_grading = \"contact\"\nfine_depth = -0.1\n"), {"mesh.fine_depth = -0.1"});
  expect_invalid_case(case_text(2, "vertical_grading = \"contact\"\nfine_depth = 0.2\nvertical_growth = 2.5\n"),
                      {"mesh.vertical_growth = 2.5", "1 < vertical_growth <= 2"});
  expect_invalid_case(case_text(2, "vertical_grading = \"contact\"\nfine_depth = 0.2\ngrading = 2\n"),
                      {"mesh.grading", "vertical_grading = \"contact\""});
  expect_invalid_case(case_text(2, "fine_depth = 0.2\n"), {"mesh.fine_depth", "only for mesh.vertical_grading"});
  expect_invalid_case(case_text(3, "vertical_growth = 1.3\n"), {"mesh.vertical_growth", "only for"});
  // 8 layers cannot grow from at least 0.01 m to the top by a ratio <= 1.05: named by the cells.
  expect_invalid_case(case_text(2, "vertical_grading = \"contact\"\nfine_depth = 0.01\nvertical_growth = 1.05\n"),
                      {"mesh.cells", "mesh.cells[vertical] = 8"});
}

// [mesh] element (docs/case-format.md): the grid's Q1 cells by default, P1 simplices on request,
// the name of the other dimension or an unknown name refused naming the field and the choices.
TEST(CaseMeshElement, ChoosesTheCellsAndRefusesNamesOfTheOtherDimension) {
  EXPECT_EQ(parse_case(case_text(3, ""), "case.toml").body.resolution.element_family,
            mesh::ElementFamily::kTensorProduct);
  EXPECT_EQ(parse_case(case_text(3, "element = \"hex8\"\n"), "case.toml").body.resolution.element_family,
            mesh::ElementFamily::kTensorProduct);
  EXPECT_EQ(parse_case(case_text(3, "element = \"tet4\"\n"), "case.toml").body.resolution.element_family,
            mesh::ElementFamily::kSimplex);
  EXPECT_EQ(parse_case(case_text(2, "element = \"tri3\"\n"), "case.toml").body.resolution.element_family,
            mesh::ElementFamily::kSimplex);
  expect_invalid_case(case_text(2, "element = \"tet4\"\n"), {"mesh.element = \"tet4\"", "\"quad4\"", "\"tri3\"", "2D body"});
  expect_invalid_case(case_text(3, "element = \"tet10\"\n"), {"mesh.element = \"tet10\"", "\"hex8\"", "\"tet4\""});
  expect_invalid_case(case_text(3, "element = 4\n"), {"mesh.element"});
}

}  // namespace
}  // namespace frictopt::io
