// SPDX-License-Identifier: MIT
// The three Delassus operators (dense, from the Schur factor, through the sparse factorization)
// against a reference M = G A⁻¹ Gᵀ built independently of them: Eigen's SimplicialLDLT of the
// reduced stiffness A (not CHOLMOD, which contact::dense_delassus and FactorizedDelassus share),
// with G and Gᵀ applied column by column through ContactBoundary; on a small 3D body whose
// contact DOFs are ordered last as in study::ElasticBody.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <memory>
#include <vector>

#include "frictopt/contact/contact_boundary.hpp"
#include "frictopt/contact/delassus.hpp"
#include "frictopt/fem/linear_elasticity.hpp"
#include "frictopt/mesh/structured_mesh.hpp"

namespace frictopt::contact {
namespace {

class DelassusOperators : public ::testing::Test {
 protected:
  DelassusOperators()
      : mesh_(mesh::StructuredMesh(shape::BezierShape::surface(1.0, 1.0, 3, 3), 0.5, {{5, 4, 3}, 1.0}).take_mesh()),
        fem_(mesh_, {2.1e11, 0.3, fem::PlaneModel::kPlaneStrain},
             fem::expand_dirichlet(mesh_, {{"top", {}, {}}}), {}),
        boundary_(mesh_, fem_.dofs()) {
    Eigen::VectorXd alpha(9);
    for (int k = 0; k < 9; ++k) alpha(k) = 0.01 + 0.004 * k;
    std::vector<int> trailing;
    for (Eigen::Index i = 0; i < boundary_.num_nodes(); ++i)
      for (int c = 0; c < 3; ++c) trailing.push_back(boundary_.free_dof(i, c));
    fem_.set_trailing_dofs(trailing);
    fem_.assemble(mesh_.positions(alpha));
    EXPECT_EQ(fem_.factorize(), Status::kConverged);
    // Reference: column j of M is G A⁻¹ Gᵀ e_j, with A⁻¹ from Eigen's own sparse LDLᵀ.
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(fem_.stiffness());
    EXPECT_EQ(ldlt.info(), Eigen::Success);
    EXPECT_EQ(fem_.stiffness().rows(), boundary_.num_free());
    const Eigen::Index m = boundary_.num_unknowns();
    reference_.resize(m, m);
    for (Eigen::Index j = 0; j < m; ++j) {
      Eigen::VectorXd w = Eigen::VectorXd::Zero(boundary_.num_free());
      boundary_.add_transpose_times(Eigen::VectorXd::Unit(m, j), w);
      const Eigen::VectorXd v = ldlt.solve(w);
      reference_.col(j) = boundary_.times(v);
    }
  }

  mesh::Mesh mesh_;
  fem::LinearElasticity fem_;
  ContactBoundary boundary_;
  Eigen::MatrixXd reference_;
};

TEST_F(DelassusOperators, AllThreeAgreeWithTheReference) {
  const Eigen::Index m = boundary_.num_unknowns();
  ASSERT_EQ(m, 3 * 6 * 5);
  const SchurDelassus schur(fem_.factorization().trailing_factor(), 3);
  const FactorizedDelassus factorized(fem_.factorization(), boundary_);
  const Eigen::MatrixXd from_schur = schur.dense();  // dpotri
  const DenseDelassus dense(std::make_shared<const Eigen::MatrixXd>(from_schur));
  const double scale = reference_.norm();
  EXPECT_LE((from_schur - reference_).norm(), 1e-12 * scale);
  EXPECT_LE((from_schur - from_schur.transpose()).norm(), 0.0);

  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(m, -1.0, 2.0).array().sin();
  const Eigen::VectorXd expected = reference_ * x;
  for (const DelassusMatrix* op : std::initializer_list<const DelassusMatrix*>{&schur, &factorized, &dense}) {
    SCOPED_TRACE(op->kind());
    Eigen::VectorXd y(m);
    op->apply(x, y);
    EXPECT_LE((y - expected).norm(), 1e-12 * expected.norm());
    EXPECT_LE((op->diagonal() - reference_.diagonal()).norm(), 1e-12 * reference_.diagonal().norm());
    // An unsorted block with repeated and overlapping indices, as the adjoint asks for.
    const std::vector<Eigen::Index> rows{7, 2, 40, 2, m - 1}, cols{m - 1, 0, 7, 33};
    const Eigen::MatrixXd b = op->block(rows, cols);
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (std::size_t j = 0; j < cols.size(); ++j)
        EXPECT_NEAR(b(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)), reference_(rows[i], cols[j]),
                    1e-12 * reference_.cwiseAbs().maxCoeff());
  }
}

}  // namespace
}  // namespace frictopt::contact
