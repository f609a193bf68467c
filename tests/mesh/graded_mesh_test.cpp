// SPDX-License-Identifier: MIT
// In-plane graded structured grids (docs/case-format.md, "[mesh]"): the column lines, the morph
// X_ref + V α on them, and the refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "common/finite_difference.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/mesh/graded_coordinates.hpp"
#include "frictopt/mesh/structured_mesh.hpp"

namespace frictopt::mesh {
namespace {

Eigen::VectorXd wavy_design(int d, double base, double amplitude) {
  Eigen::VectorXd alpha(d);
  for (int k = 0; k < d; ++k) alpha(k) = base + amplitude * std::sin(1.7 * k + 0.3);
  return alpha;
}

// Checks the graded lines: strictly increasing from 0 to length, lo and hi are lines (exactly),
// uniform inside [lo, hi], neighbouring cells differ by a ratio <= growth, no cell outside the
// box smaller than a box cell. Returns the box cell size.
double expect_graded(const std::vector<double>& x, double length, double lo, double hi, double growth) {
  EXPECT_EQ(x.front(), 0.0);
  EXPECT_EQ(x.back(), length);
  for (std::size_t i = 0; i + 1 < x.size(); ++i) EXPECT_LT(x[i], x[i + 1]) << "line " << i;
  const auto at_lo = std::find(x.begin(), x.end(), lo), at_hi = std::find(x.begin(), x.end(), hi);
  EXPECT_NE(at_lo, x.end()) << "lo = " << lo << " is not a grid line";
  EXPECT_NE(at_hi, x.end()) << "hi = " << hi << " is not a grid line";
  if (at_lo == x.end() || at_hi == x.end()) return 0.0;
  const double h = (hi - lo) / static_cast<double>(at_hi - at_lo);
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double size = x[i + 1] - x[i];
    if (x[i] >= lo && x[i + 1] <= hi)
      EXPECT_NEAR(size, h, 1e-12 * length) << "box cell " << i;
    else
      EXPECT_GE(size, h * (1 - 1e-9)) << "side cell " << i;
    if (i + 2 < x.size()) {
      const double next = x[i + 2] - x[i + 1];
      EXPECT_LE(std::max(size / next, next / size), growth * (1 + 1e-9)) << "cells " << i << ", " << i + 1;
    }
  }
  return h;
}

TEST(GradedCoordinates, UniformIsTheFormulaOfTheUniformGrid) {
  const std::vector<double> x = uniform_coordinates(0.7, 9);
  ASSERT_EQ(x.size(), 10u);
  for (int i = 0; i <= 9; ++i) EXPECT_EQ(x[static_cast<std::size_t>(i)], 0.7 * i / 9);  // bit for bit
}

TEST(GradedCoordinates, MonotoneExactBoxEdgesAndRatioAtMostGrowth) {
  struct Case {
    double length, lo, hi, growth;
    int cells;
  };
  for (const Case& c : {Case{1.0, 0.3, 0.7, 1.2, 40}, Case{1.0, 0.3, 0.7, 1.1, 20}, Case{2.0, 0.0, 0.5, 1.3, 25},
                        Case{1.0, 0.6, 1.0, 1.5, 12}, Case{1.0, 0.1, 0.3, 1.25, 33}, Case{3.0, 1.2, 1.7, 2.0, 30}}) {
    SCOPED_TRACE(std::to_string(c.cells) + " cells, box [" + std::to_string(c.lo) + ", " + std::to_string(c.hi) +
                 "], growth " + std::to_string(c.growth));
    const std::vector<double> x = graded_coordinates(c.length, c.cells, c.lo, c.hi, c.growth, "mesh.cells[0]");
    ASSERT_EQ(x.size(), static_cast<std::size_t>(c.cells) + 1);
    const double h = expect_graded(x, c.length, c.lo, c.hi, c.growth);
    // Grading pays: the box cells are finer than the uniform grid's.
    EXPECT_LT(h, c.length / c.cells);
  }
}

TEST(GradedCoordinates, RefusesWhatCannotBeGradedNamingTheField) {
  const auto message = [](auto&& f) {
    try {
      f();
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message([] { graded_coordinates(1.0, 4, 0.45, 0.55, 1.05, "mesh.cells[1]"); }).find("mesh.cells[1] = 4"),
            std::string::npos);
  EXPECT_NE(message([] { graded_coordinates(1.0, 10, 0.7, 0.3, 1.2, "mesh.cells[0]"); }).find("mesh.refine_box"),
            std::string::npos);
  EXPECT_NE(message([] { graded_coordinates(1.0, 10, 0.3, 1.2, 1.2, "mesh.cells[0]"); }).find("mesh.refine_box"),
            std::string::npos);
  EXPECT_NE(message([] { graded_coordinates(1.0, 10, 0.3, 0.7, 2.5, "mesh.cells[0]"); }).find("mesh.growth = 2.5"),
            std::string::npos);
}

TEST(GradedStructuredMesh, ColumnsAreGradedAndTheDefaultBoxIsTheCentralThird) {
  const auto surface = shape::BezierShape::surface(1.2, 0.9, 3, 3);
  GridResolution resolution{{24, 18, 4}, 1.5};
  resolution.growth = 1.2;
  const StructuredMesh grid(surface, 1.0, resolution);
  expect_graded(grid.column_coordinates(0), 1.2, 1.2 * (1 - kDefaultRefineFraction) / 2,
                1.2 * (1 + kDefaultRefineFraction) / 2, 1.2);
  expect_graded(grid.column_coordinates(1), 0.9, 0.9 * (1 - kDefaultRefineFraction) / 2,
                0.9 * (1 + kDefaultRefineFraction) / 2, 1.2);
  // Columns are fixed: every node of column (i1, i2) has the column's x'.
  const Eigen::MatrixXd& X = grid.mesh().reference_positions();
  for (int k = 0; k <= 4; ++k) {
    EXPECT_EQ(X(grid.node(5, 7, k), 0), grid.column_coordinates(0)[5]);
    EXPECT_EQ(X(grid.node(5, 7, k), 1), grid.column_coordinates(1)[7]);
  }
}

TEST(GradedStructuredMesh, WithoutGrowthTheGridIsTheUniformOne) {
  const auto curve = shape::BezierShape::curve(2.0, 5);
  const StructuredMesh grid(curve, 1.0, {{10, 0, 3}, 1.5});
  for (int i = 0; i <= 10; ++i) EXPECT_EQ(grid.column_coordinates(0)[static_cast<std::size_t>(i)], 2.0 * i / 10);
}

// The morphed volume of a Q1 column grid is exactly Σ_cells (cell area) · (mean of the corner
// thicknesses C4 − G_α), the trapezoid rule on the graded lines, so it is affine in α; it tends
// to the exact linear formula base·C4 − wᵀα at second order when the cells shrink everywhere.
// With a fixed growth the cells at the sides do not shrink (the largest is about
// side·(growth − 1)/growth), so the refinement halves (growth − 1) with the box cell size.
TEST(GradedStructuredMesh, MorphedVolumeIsTheTrapezoidRuleAndConvergesToTheLinearFormula) {
  const auto surface = shape::BezierShape::surface(1.0, 0.8, 4, 3);
  const Eigen::VectorXd alpha = wavy_design(12, 0.25, 0.15);
  const double exact = surface.base_measure() * 1.0 - surface.integral_weights().dot(alpha);
  std::vector<double> errors, largest;
  for (const auto& [n, growth] : {std::pair{12, 1.4}, std::pair{24, 1.2}, std::pair{48, 1.1}}) {
    GridResolution resolution{{n, n, 2}, 1.0};
    resolution.growth = growth;
    resolution.refine_box = std::array<double, 4>{0.3, 0.6, 0.2, 0.5};
    const StructuredMesh grid(surface, 1.0, resolution);
    const std::vector<double>& x1 = grid.column_coordinates(0);
    const std::vector<double>& x2 = grid.column_coordinates(1);
    double trapezoid = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        double mean = 0;
        for (int a : {0, 1})
          for (int b : {0, 1})
            mean += 0.25 * (1.0 - surface.height(alpha, Eigen::Vector2d(x1[static_cast<std::size_t>(i + a)],
                                                                        x2[static_cast<std::size_t>(j + b)])));
        trapezoid += (x1[static_cast<std::size_t>(i) + 1] - x1[static_cast<std::size_t>(i)]) *
                     (x2[static_cast<std::size_t>(j) + 1] - x2[static_cast<std::size_t>(j)]) * mean;
      }
    const Mesh& mesh = grid.mesh();
    const double volume = mesh.volume(mesh.positions(alpha));
    EXPECT_NEAR(volume, trapezoid, 1e-13) << n << " cells";
    // Affine in α: V(α) = V(0) + (V(2α) − V(0))/2 exactly up to round-off.
    const double v0 = mesh.volume(mesh.positions(Eigen::VectorXd::Zero(12)));
    EXPECT_NEAR(volume, v0 + 0.5 * (mesh.volume(mesh.positions(2 * alpha)) - v0), 1e-13) << n << " cells";
    errors.push_back(std::abs(volume - exact));
    double h = 0;
    for (const std::vector<double>* x : {&x1, &x2})
      for (std::size_t i = 0; i + 1 < x->size(); ++i) h = std::max(h, (*x)[i + 1] - (*x)[i]);
    largest.push_back(h);
    std::printf("graded 3D volume: %d cells, growth %.1f, largest cell %.4f m, error %.3e\n", n, growth, h,
                errors.back());
  }
  // Second order in the largest cell, measured over the whole sequence (the steps in between
  // are pre-asymptotic: the side cells and the box cells shrink at different paces).
  const double rate = std::log(errors.front() / errors.back()) / std::log(largest.front() / largest.back());
  std::printf("graded 3D volume: observed rate in the largest cell %.3f\n", rate);
  EXPECT_GT(rate, 1.7);
}

TEST(GradedStructuredMesh, DesignJacobianMatchesCentralDifferences) {
  for (int dim : {2, 3}) {
    const auto shape = dim == 2 ? shape::BezierShape::curve(1.0, 5) : shape::BezierShape::surface(1.0, 1.0, 3, 3);
    GridResolution resolution{{14, 12, 3}, 2.0};
    resolution.growth = 1.3;
    resolution.refine_box = std::array<double, 4>{0.2, 0.45, 0.5, 0.9};
    const StructuredMesh grid(shape, 1.0, resolution);
    const Eigen::VectorXd alpha = wavy_design(shape.num_controls(), 0.2, 0.1);
    const auto positions = [&](const Eigen::VectorXd& a) {
      const Eigen::MatrixXd X = grid.mesh().positions(a);
      Eigen::VectorXd flat(X.size());
      for (int n = 0; n < X.rows(); ++n) flat.segment(n * dim, dim) = X.row(n).transpose();
      return flat;
    };
    const Eigen::MatrixXd fd =
        frictopt::testing::central_jacobian(positions, alpha, frictopt::testing::central_step(alpha));
    const Eigen::MatrixXd V = Eigen::MatrixXd(grid.mesh().design_jacobian());
    EXPECT_LE((fd - V).norm(), 1e-9 * V.norm()) << dim << "D";
    // The bottom is the Bézier surface at the actual (graded) column positions.
    const Eigen::MatrixXd X = grid.mesh().positions(alpha);
    for (int node : grid.face(Face::kBottom).nodes)
      EXPECT_NEAR(X(node, dim - 1), shape.height(alpha, X.row(node).head(dim - 1).transpose()), 1e-15);
  }
}

TEST(GradedStructuredMesh, RejectsABoxWithoutGrowthAndAGrowthOutOfRange) {
  const auto curve = shape::BezierShape::curve(1.0, 3);
  GridResolution resolution{{8, 0, 2}, 1.0};
  resolution.refine_box = std::array<double, 4>{0.2, 0.4, 0.0, 0.0};
  EXPECT_THROW(StructuredMesh(curve, 1.0, resolution), InvalidInput);
  resolution.growth = 2.5;
  EXPECT_THROW(StructuredMesh(curve, 1.0, resolution), InvalidInput);
}

}  // namespace
}  // namespace frictopt::mesh
