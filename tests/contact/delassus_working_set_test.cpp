// SPDX-License-Identifier: MIT
// SchurDelassus::principal_block (triangular solves for the block's columns, cached and
// extended) against dpotri's dense M, and WorkingSetCoulombSolver against CoulombSolver on the
// dense M: a 3D body whose 13 × 13 bottom nodes are pressed by a paraboloid-shaped gap (the
// contact zone holds about a third of them) and dragged sideways.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "frictopt/contact/contact_boundary.hpp"
#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/contact/delassus.hpp"
#include "frictopt/contact/working_set_coulomb.hpp"
#include "frictopt/fem/linear_elasticity.hpp"
#include "frictopt/mesh/structured_mesh.hpp"

namespace frictopt::contact {
namespace {

class WorkingSet : public ::testing::Test {
 protected:
  WorkingSet()
      : mesh_(mesh::StructuredMesh(shape::BezierShape::surface(1.0, 1.0, 3, 3), 0.5, {{12, 12, 3}, 1.0}).take_mesh()),
        fem_(mesh_, {1e9, 0.3, fem::PlaneModel::kPlaneStrain}, fem::expand_dirichlet(mesh_, {{"top", {}, {}}}), {}),
        boundary_(mesh_, fem_.dofs()) {
    std::vector<int> trailing;
    for (Eigen::Index i = 0; i < boundary_.num_nodes(); ++i)
      for (int c = 0; c < 3; ++c) trailing.push_back(boundary_.free_dof(i, c));
    fem_.set_trailing_dofs(trailing);
    fem_.assemble(mesh_.positions(Eigen::VectorXd::Zero(9)));
    EXPECT_EQ(fem_.factorize(), Status::kConverged);
    schur_ = std::make_unique<SchurDelassus>(fem_.factorization().trailing_factor(), 3);
    dense_ = schur_->dense();
  }

  /// c of a rigid paraboloid r²/(2R) pressed `depth` into the bottom and the body moved by
  /// `shift` along x1: c_ν = gap − depth, c_q = −u_t = −shift (the free body's response).
  Eigen::VectorXd linear_term(double depth, double shift) const {
    const Eigen::MatrixXd& x = boundary_.plane_coordinates();
    Eigen::VectorXd c = Eigen::VectorXd::Zero(boundary_.num_unknowns());
    for (Eigen::Index i = 0; i < boundary_.num_nodes(); ++i) {
      const double r2 = (x.row(i).array() - 0.5).square().sum();
      c(3 * i) = -shift;
      c(3 * i + 2) = r2 / (2 * 2.0) - depth;
    }
    return c;
  }

  mesh::Mesh mesh_;
  fem::LinearElasticity fem_;
  ContactBoundary boundary_;
  std::unique_ptr<SchurDelassus> schur_;
  Eigen::MatrixXd dense_;
};

TEST_F(WorkingSet, PrincipalBlocksMatchTheDenseMatrixAndGrow) {
  const double scale = dense_.cwiseAbs().maxCoeff();
  const auto expect_block = [&](const std::vector<Eigen::Index>& rows, const std::vector<Eigen::Index>& cols,
                                const Eigen::MatrixXd& b) {
    ASSERT_EQ(b.rows(), static_cast<Eigen::Index>(rows.size()));
    ASSERT_EQ(b.cols(), static_cast<Eigen::Index>(cols.size()));
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (std::size_t j = 0; j < cols.size(); ++j)
        EXPECT_NEAR(b(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)), dense_(rows[i], cols[j]), 1e-12 * scale);
  };
  // Unsorted indices spread over the whole range (more than one solve group of 192 columns).
  const Eigen::Index m = schur_->size();
  std::vector<Eigen::Index> first;
  for (Eigen::Index k = m - 1; k >= 0; k -= 2) first.push_back(k);
  expect_block(first, first, schur_->principal_block(first));
  EXPECT_EQ(schur_->cached_indices().size(), first.size());
  // A superset: only the new columns are solved; the block comes in the requested order.
  std::vector<Eigen::Index> second{0, 1, 5, 4};
  second.insert(second.end(), first.begin(), first.begin() + 30);
  expect_block(second, second, schur_->principal_block(second));
  EXPECT_EQ(schur_->cached_indices().size(), first.size() + 2);  // 1, 5 are new; 0, 4 were cached (m − 1 is even)
  // block() inside the cache reads it, outside it solves; both agree with dpotri's M.
  const std::vector<Eigen::Index> rows{1, 5, 0, 5}, cols{m - 1, 4};
  expect_block(rows, cols, schur_->block(rows, cols));
  const std::vector<Eigen::Index> outside{3, 7};
  expect_block(outside, rows, schur_->block(outside, rows));
  // Without the columns the block still answers; a request outside it starts the cache over.
  schur_->release_block_columns();
  expect_block(rows, cols, schur_->block(rows, cols));
  const std::vector<Eigen::Index> third{3, 1, 7};
  expect_block(third, third, schur_->principal_block(third));
  EXPECT_EQ(schur_->cached_indices().size(), 3u);
  schur_->release_block_cache();
  EXPECT_TRUE(schur_->cached_indices().empty());
  expect_block(rows, cols, schur_->block(rows, cols));
}

void expect_same_solution(const SchurDelassus& schur, const Eigen::MatrixXd& dense, const FrictionLaw& law,
                          const Eigen::VectorXd& c) {
  CoulombSolver::Options options;
  const DenseDelassus full(dense);
  ContactState reference;
  const CoulombSolver::Summary expected = CoulombSolver(full, law, options).solve(c, reference);
  ASSERT_TRUE(expected.converged()) << expected.message;
  ContactState state;
  const WorkingSetCoulombSolver::Summary s = WorkingSetCoulombSolver(schur, law, options).solve(c, state);
  ASSERT_TRUE(s.coulomb.converged()) << s.coulomb.message;
  EXPECT_LE(s.coulomb.kkt_residual, 1e-8);
  EXPECT_LE(s.coulomb.complementarity_gap, 1e-8);
  EXPECT_LE((state.z - reference.z).norm(), 1e-7 * reference.z.norm());
  EXPECT_LE((state.gradient - (dense * state.z + c)).norm(), 1e-10 * c.norm());
  Eigen::Index loaded = 0;
  for (Eigen::Index i = 0; i < state.num_nodes(); ++i) loaded += state.lambda(i) > 0;
  // The working set is smaller than the body's bottom, and holds every loaded node.
  EXPECT_LT(s.final_nodes, state.num_nodes());
  EXPECT_GE(s.final_nodes, loaded);
  EXPECT_GT(loaded, 10);
  for (std::size_t i = 0; i < state.nodes.size(); ++i)
    EXPECT_EQ(state.nodes[i].status, reference.nodes[i].status) << "node " << i;
  // A warm start from the solution converges in the first working set.
  const WorkingSetCoulombSolver::Summary again = WorkingSetCoulombSolver(schur, law, options).solve(c, state);
  ASSERT_TRUE(again.coulomb.converged());
  EXPECT_EQ(again.rounds, 1);
  EXPECT_LE((state.z - reference.z).norm(), 1e-7 * reference.z.norm());
}

TEST_F(WorkingSet, FrictionlessAgreesWithTheFullProblem) {
  expect_same_solution(*schur_, dense_, FrictionLaw::disc(0.0), linear_term(0.01, 0.0));
}

TEST_F(WorkingSet, CoulombWithPartialSlipAgreesWithTheFullProblem) {
  expect_same_solution(*schur_, dense_, FrictionLaw::regular_polygon(0.3, 8), linear_term(0.01, 0.002));
}

TEST_F(WorkingSet, NoPenetrationMeansNoContact) {
  ContactState state;
  const Eigen::VectorXd c = linear_term(-0.01, 0.001);  // lifted 1 cm
  const WorkingSetCoulombSolver::Summary s =
      WorkingSetCoulombSolver(*schur_, FrictionLaw::disc(0.3), CoulombSolver::Options{}).solve(c, state);
  ASSERT_TRUE(s.coulomb.converged());
  EXPECT_EQ(s.final_nodes, 0);
  EXPECT_EQ(state.z.norm(), 0.0);
  EXPECT_EQ((state.gradient - c).norm(), 0.0);
}

}  // namespace
}  // namespace frictopt::contact
