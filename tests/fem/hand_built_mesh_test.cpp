// SPDX-License-Identifier: MIT
// fem on a mesh::Mesh that no grid produced: scrambled node numbers, a distorted interior node,
// boundary sets given by hand. The element kernels and assembly must not depend on the
// structured producer's numbering (docs/architecture.md, "a new mesh source").
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "frictopt/fem/linear_elasticity.hpp"
#include "frictopt/mesh/mesh.hpp"

namespace frictopt::fem {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// 2 × 2 quadrilaterals on [0, 2]², the centre node moved to (0.83, 1.21); node numbers follow a
// fixed scrambling of the row-major grid numbering.
mesh::Mesh scrambled_patch() {
  const std::array<int, 9> number{4, 7, 0, 2, 8, 5, 1, 6, 3};  // grid node g -> mesh node number[g]
  Eigen::MatrixXd X(9, 2);
  for (int g = 0; g < 9; ++g) X.row(number[g]) << g % 3, g / 3;
  X.row(number[4]) << 0.83, 1.21;
  const auto n = [&](int i, int j) { return number[static_cast<std::size_t>(i + 3 * j)]; };
  mesh::Connectivity cells(4, 4);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) cells.row(i + 2 * j) << n(i, j), n(i + 1, j), n(i + 1, j + 1), n(i, j + 1);
  mesh::BoundarySet outer;
  outer.facets.resize(8, 2);
  outer.facets << n(0, 0), n(1, 0), n(1, 0), n(2, 0), n(2, 0), n(2, 1), n(2, 1), n(2, 2), n(2, 2), n(1, 2), n(1, 2),
      n(0, 2), n(0, 2), n(0, 1), n(0, 1), n(0, 0);
  for (int g = 0; g < 9; ++g)
    if (g != 4) outer.nodes.push_back(number[static_cast<std::size_t>(g)]);
  std::sort(outer.nodes.begin(), outer.nodes.end());
  std::map<std::string, mesh::BoundarySet, std::less<>> sets;
  sets["outer"] = outer;
  return mesh::Mesh(mesh::ElementKind::kQuad4, X, cells, Eigen::SparseMatrix<double>(18, 0), sets);
}

// Patch test: a linear displacement prescribed on the boundary is reproduced exactly inside.
TEST(HandBuiltMesh, PassesThePatchTestWithScrambledNumbering) {
  const mesh::Mesh mesh = scrambled_patch();
  const auto field = [](const Eigen::Vector2d& x) {
    return Eigen::Vector2d(1e-3 + 2e-3 * x(0) - 1e-3 * x(1), -5e-4 + 1e-3 * x(0) + 3e-3 * x(1));
  };
  PrescribedDofs dirichlet;
  for (int node : mesh.boundary("outer").nodes) {
    const Eigen::Vector2d u = field(mesh.reference_positions().row(node).transpose());
    for (int c = 0; c < 2; ++c) {
      dirichlet.dofs.push_back(2 * node + c);
      dirichlet.values.push_back(u(c));
    }
  }
  LinearElasticity problem(mesh, {2e11, 0.3, PlaneModel::kPlaneStrain}, dirichlet, {});
  ASSERT_EQ(problem.dofs().num_free(), 2);  // the centre node only
  problem.assemble(mesh.reference_positions());
  ASSERT_EQ(problem.factorize(), Status::kConverged) << problem.factorization().message();
  const Eigen::VectorXd u = problem.solve();
  const int centre = 8;  // number[4]
  const Eigen::Vector2d expected = field(mesh.reference_positions().row(centre).transpose());
  // Q1 reproduces linear fields on any convex quadrilaterals: exact up to round-off.
  EXPECT_LE((u.segment<2>(2 * centre) - expected).norm(), 100 * kEps * expected.norm());
  // The reactions balance: the residual's sum over all nodes vanishes without body loads.
  const Eigen::VectorXd r = problem.residual(mesh.reference_positions(), u);
  Eigen::Vector2d total = Eigen::Vector2d::Zero();
  for (int node = 0; node < mesh.num_nodes(); ++node) total += r.segment<2>(2 * node);
  EXPECT_LE(total.norm(), 1e3 * kEps * r.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace frictopt::fem
