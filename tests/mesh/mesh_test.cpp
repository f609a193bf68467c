// SPDX-License-Identifier: MIT
// mesh::Mesh built by hand (no producer): the design motion, geometry and the invariants its
// constructor checks.
#include "frictopt/mesh/mesh.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "frictopt/core/error.hpp"

namespace frictopt::mesh {
namespace {

// One unit square cell (VTK order) whose top edge moves up with the single design variable.
struct OneSquare {
  Eigen::MatrixXd reference{{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}};
  Connectivity cells{{0, 1, 2, 3}};
  Eigen::SparseMatrix<double> V{8, 1};
  std::map<std::string, BoundarySet, std::less<>> boundaries;
  OneSquare() {
    V.insert(2 * 2 + 1, 0) = 1.0;  // node 2, component y
    V.insert(3 * 2 + 1, 0) = 1.0;  // node 3, component y
    V.makeCompressed();
    boundaries["top"] = {Connectivity{{2, 3}}, {2, 3}};
    boundaries["bottom"] = {Connectivity{{0, 1}}, {0, 1}};
  }
  Mesh build() const { return Mesh(ElementKind::kQuad4, reference, cells, V, boundaries); }
};

TEST(Mesh, PositionsAreReferencePlusDesignJacobianTimesAlpha) {
  const Mesh mesh = OneSquare().build();
  EXPECT_EQ(mesh.dim(), 2);
  EXPECT_EQ(mesh.num_nodes(), 4);
  EXPECT_EQ(mesh.num_dofs(), 8);
  EXPECT_EQ(mesh.num_design_variables(), 1);
  const Eigen::MatrixXd X = mesh.positions(Eigen::VectorXd::Constant(1, 0.5));
  EXPECT_EQ(X(2, 1), 1.5);
  EXPECT_EQ(X(3, 1), 1.5);
  EXPECT_EQ(X(1, 1), 0.0);
  // A bilinear cell's area is exact under the 2×2 Gauss rule: 1 × 1.5.
  EXPECT_NEAR(mesh.volume(X), 1.5, 1e-15);
  EXPECT_NO_THROW(mesh.check_quality(X, "design 1"));
  EXPECT_TRUE(mesh.has_boundary("top"));
  EXPECT_FALSE(mesh.has_boundary("left"));
  EXPECT_EQ(mesh.boundary("bottom").nodes, (std::vector<int>{0, 1}));
}

TEST(Mesh, ReportsAnInvertedCellWithoutAProducerLocation) {
  const Mesh mesh = OneSquare().build();
  try {
    mesh.check_quality(mesh.positions(Eigen::VectorXd::Constant(1, -2.0)), "design 7");
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()).rfind("element 0 is inverted for the design 7", 0), 0u) << e.what();
  }
}

TEST(Mesh, ConstructorRefusesInconsistentParts) {
  OneSquare bad_index;
  bad_index.cells(0, 3) = 4;
  EXPECT_THROW((void)bad_index.build(), InvalidInput);
  OneSquare bad_jacobian;
  bad_jacobian.V.resize(6, 1);
  EXPECT_THROW((void)bad_jacobian.build(), InvalidInput);
  OneSquare bad_set;
  bad_set.boundaries["top"].nodes = {3, 2};  // not increasing
  EXPECT_THROW((void)bad_set.build(), InvalidInput);
  OneSquare bad_facet;
  bad_facet.boundaries["left"] = {Connectivity{{0, 3, 2}}, {0, 2, 3}};  // 3-node facet on quads
  EXPECT_THROW((void)bad_facet.build(), InvalidInput);
  OneSquare wrong_kind;
  EXPECT_THROW(Mesh(ElementKind::kHex8, wrong_kind.reference, wrong_kind.cells, wrong_kind.V, wrong_kind.boundaries),
               InvalidInput);
}

TEST(ElementKind, NamesRoundTrip) {
  for (ElementKind kind : {ElementKind::kQuad4, ElementKind::kHex8, ElementKind::kTri3, ElementKind::kTet4}) {
    EXPECT_EQ(parse_element_kind(to_string(kind)), kind);
    EXPECT_EQ(element_kind(family_of(kind), spatial_dimension(kind)), kind);
  }
  EXPECT_THROW((void)parse_element_kind("tet10"), InvalidInput);
}

}  // namespace
}  // namespace frictopt::mesh
