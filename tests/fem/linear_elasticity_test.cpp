// SPDX-License-Identifier: MIT
#include "frictopt/fem/linear_elasticity.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include "../../src/fem/element_kernels.hpp"
#include "common/finite_difference.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/fem/stress_recovery.hpp"
#include "frictopt/mesh/structured_mesh.hpp"

namespace frictopt::fem {
namespace {

using frictopt::testing::kSeed;
constexpr double kEps = std::numeric_limits<double>::epsilon();

shape::BezierShape make_shape(int dim) {
  return dim == 2 ? shape::BezierShape::curve(2.0, 5) : shape::BezierShape::surface(1.0, 0.8, 3, 3);
}

Eigen::VectorXd curved_design(int d) {
  Eigen::VectorXd alpha(d);
  for (int k = 0; k < d; ++k) alpha(k) = 0.15 + 0.1 * std::sin(2.1 * k + 0.4);
  return alpha;
}

mesh::GridResolution resolution(int dim, int n, mesh::ElementFamily family = mesh::ElementFamily::kTensorProduct) {
  mesh::GridResolution r = dim == 2 ? mesh::GridResolution{{2 * n, 0, n}, 1.0} : mesh::GridResolution{{n, n, n}, 1.0};
  r.element_family = family;
  return r;
}

// Prescribes the values of a vector field on every boundary node (all faces, bottom included).
template <class Field>
PrescribedDofs prescribe_on_boundary(const mesh::Mesh& mesh, const Eigen::MatrixXd& X, Field field) {
  std::map<int, double> values;
  for (const std::string& name : mesh.boundary_names())  // every face of the grid
    for (int node : mesh.boundary(name).nodes) {
      const Eigen::VectorXd u = field(Eigen::VectorXd(X.row(node).transpose()));
      for (int c = 0; c < mesh.dim(); ++c) values[node * mesh.dim() + c] = u(c);
    }
  PrescribedDofs p;
  for (auto [dof, v] : values) {
    p.dofs.push_back(dof);
    p.values.push_back(v);
  }
  return p;
}

const IsotropicMaterial kSteel{2.1e11, 0.3, PlaneModel::kPlaneStrain};

class ElasticityByDimension : public ::testing::TestWithParam<int> {};

// The tests every element class must pass: Q1 and P1 (the grid split into simplices) in 2D and 3D.
struct ElementCase {
  int dim;
  mesh::ElementFamily family;
};
class ElasticityByElement : public ::testing::TestWithParam<ElementCase> {};

TEST_P(ElasticityByElement, PatchTestReproducesLinearFieldToRoundOff) {
  const int dim = GetParam().dim;
  const mesh::ElementFamily family = GetParam().family;
  const auto s = make_shape(dim);
  const mesh::Mesh mesh = mesh::StructuredMesh(s, 1.0, resolution(dim, 4, family)).take_mesh();
  const Eigen::MatrixXd X = mesh.positions(curved_design(s.num_controls()));
  Eigen::MatrixXd B(dim, dim);
  B.setZero();
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j) B(i, j) = 1e-3 * (1 + i + 2 * j) * (i == j ? 1.0 : -0.5);
  const auto linear = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
    return Eigen::VectorXd::Constant(dim, 1e-4) + B * x;
  };
  LinearElasticity problem(mesh, kSteel, prescribe_on_boundary(mesh, X, linear), {});
  problem.assemble(X);
  ASSERT_EQ(problem.factorize(), Status::kConverged);
  const Eigen::VectorXd u = problem.solve();
  double max_error = 0.0, max_value = 0.0;
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    const Eigen::VectorXd exact = linear(X.row(n).transpose());
    max_error = std::max(max_error, (u.segment(n * dim, dim) - exact).cwiseAbs().maxCoeff());
    max_value = std::max(max_value, exact.cwiseAbs().maxCoeff());
  }
  // Backward-stable Cholesky on a well-conditioned small system: error ~ cond·eps.
  EXPECT_LE(max_error, 1e4 * kEps * max_value) << "dim " << dim;
  // The stress is the constant C ε(B) everywhere.
  const StressField stress = recover_stresses(mesh, kSteel, X, u);
  const Eigen::VectorXd spread = (stress.element.colwise().maxCoeff() - stress.element.colwise().minCoeff()).transpose();
  EXPECT_LE(spread.maxCoeff(), 1e-6 * stress.element.cwiseAbs().maxCoeff());
}

TEST_P(ElasticityByDimension, ManufacturedHarmonicSolutionConvergesAtSecondOrderInL2) {
  // u = ∇φ with φ harmonic satisfies μΔu + (λ+μ)∇div u = 0 with no body force: an exact
  // solution on the curved body when its boundary values are prescribed.
  const int dim = GetParam();
  const auto s = make_shape(dim);
  const auto exact = [dim](const Eigen::VectorXd& x) -> Eigen::VectorXd {
    Eigen::VectorXd u(dim);
    const double scale = 1e-3;
    if (dim == 2) {
      u << std::exp(x(0)) * std::cos(x(1)), -std::exp(x(0)) * std::sin(x(1));
    } else {
      const double r = 1.0 / std::sqrt(2.0);
      const double e = std::exp(x(0)), cy = std::cos(r * x(1)), sy = std::sin(r * x(1)),
                   cz = std::cos(r * x(2)), sz = std::sin(r * x(2));
      u << e * cy * cz, -r * e * sy * cz, -r * e * cy * sz;
    }
    return scale * u;
  };
  std::vector<double> errors;
  const std::vector<int> levels = dim == 2 ? std::vector<int>{4, 8, 16} : std::vector<int>{2, 4, 8};
  for (int n : levels) {
    const mesh::Mesh mesh = mesh::StructuredMesh(s, 1.0, resolution(dim, n)).take_mesh();
    const Eigen::MatrixXd X = mesh.positions(curved_design(s.num_controls()));
    LinearElasticity problem(mesh, kSteel, prescribe_on_boundary(mesh, X, exact), {});
    problem.assemble(X);
    ASSERT_EQ(problem.factorize(), Status::kConverged);
    const Eigen::VectorXd u = problem.solve();
    // L2 error by 3-point Gauss per direction (the 2-point rule would hide part of the error).
    double error2 = 0.0;
    const double g[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, w[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
    for (int e = 0; e < mesh.num_elements(); ++e) {
      const int nq = dim == 2 ? 9 : 27;
      for (int q = 0; q < nq; ++q) {
        const int q0 = q % 3, q1 = (q / 3) % 3, q2 = q / 9;
        double weight = w[q0] * w[q1] * (dim == 3 ? w[q2] : 1.0);
        if (dim == 2) {
          using El = mesh::Q1Element<2>;
          const El::Point xi(g[q0], g[q1]);
          const auto N = El::values(xi);
          const auto dN = El::gradients(xi);
          Eigen::Matrix<double, 4, 2> Xe;
          Eigen::Vector2d uh = Eigen::Vector2d::Zero();
          for (int a = 0; a < 4; ++a) {
            Xe.row(a) = X.row(mesh.elements()(e, a));
            uh += N(a) * u.segment<2>(mesh.elements()(e, a) * 2);
          }
          const Eigen::Vector2d x = Xe.transpose() * N;
          weight *= (Xe.transpose() * dN).determinant();
          error2 += weight * (uh - exact(x)).squaredNorm();
        } else {
          using El = mesh::Q1Element<3>;
          const El::Point xi(g[q0], g[q1], g[q2]);
          const auto N = El::values(xi);
          const auto dN = El::gradients(xi);
          Eigen::Matrix<double, 8, 3> Xe;
          Eigen::Vector3d uh = Eigen::Vector3d::Zero();
          for (int a = 0; a < 8; ++a) {
            Xe.row(a) = X.row(mesh.elements()(e, a));
            uh += N(a) * u.segment<3>(mesh.elements()(e, a) * 3);
          }
          const Eigen::Vector3d x = Xe.transpose() * N;
          weight *= (Xe.transpose() * dN).determinant();
          error2 += weight * (uh - exact(x)).squaredNorm();
        }
      }
    }
    errors.push_back(std::sqrt(error2));
  }
  for (std::size_t i = 0; i + 1 < errors.size(); ++i) {
    const double rate = std::log2(errors[i] / errors[i + 1]);
    std::printf("dim %d: L2 error %.4e -> %.4e, observed rate %.3f\n", dim, errors[i], errors[i + 1], rate);
    // Q1 elements: O(h²) in L2; the coarsest pair is still pre-asymptotic, hence ±0.3.
    EXPECT_NEAR(rate, 2.0, 0.3) << "levels " << i << "," << i + 1;
  }
}

TEST_P(ElasticityByElement, StiffnessIsSymmetricPositiveDefiniteAfterDirichlet) {
  const int dim = GetParam().dim;
  const mesh::ElementFamily family = GetParam().family;
  const auto s = make_shape(dim);
  const mesh::Mesh mesh = mesh::StructuredMesh(s, 1.0, resolution(dim, 2, family)).take_mesh();
  const Eigen::MatrixXd X = mesh.positions(curved_design(s.num_controls()));
  LinearElasticity problem(mesh, kSteel, expand_dirichlet(mesh, {{"left", {}, {}}}), {});
  problem.assemble(X);
  const Eigen::MatrixXd A = Eigen::MatrixXd(problem.stiffness());
  EXPECT_LE((A - A.transpose()).norm(), 20 * kEps * A.norm());
  const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A).eigenvalues();
  EXPECT_GT(eig.minCoeff(), 1e-8 * eig.maxCoeff()) << "smallest " << eig.minCoeff();
  // Without Dirichlet conditions the full stiffness has the rigid modes: dim(dim+1)/2 zeros.
  LinearElasticity free_body(mesh, kSteel, {}, {});
  free_body.assemble(X);
  const Eigen::VectorXd eig_free =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(free_body.stiffness())).eigenvalues();
  const int rigid = dim * (dim + 1) / 2;
  EXPECT_LE(std::abs(eig_free(rigid - 1)), 1e-9 * eig_free.maxCoeff());
  EXPECT_GT(eig_free(rigid), 1e-6 * eig_free.maxCoeff());
}

TEST_P(ElasticityByElement, TractionResultantAndClapeyronEnergyBalance) {
  const int dim = GetParam().dim;
  const mesh::ElementFamily family = GetParam().family;
  const auto s = make_shape(dim);
  const mesh::Mesh mesh = mesh::StructuredMesh(s, 1.0, resolution(dim, 3, family)).take_mesh();
  const Eigen::MatrixXd X = mesh.positions(curved_design(s.num_controls()));
  Eigen::VectorXd t = Eigen::VectorXd::Zero(dim);
  t(0) = 2e6;
  t(dim - 1) = -5e6;
  LinearElasticity problem(mesh, kSteel, expand_dirichlet(mesh, {{"left", {}, {}}}),
                           {{"top", t}});
  const Eigen::VectorXd l = problem.traction_load(X);
  Eigen::VectorXd resultant = Eigen::VectorXd::Zero(dim);
  for (int n = 0; n < mesh.num_nodes(); ++n) resultant += l.segment(n * dim, dim);
  const double top_area = dim == 2 ? 2.0 : 0.8;
  EXPECT_LE((resultant - top_area * t).norm(), 1e-12 * t.norm());
  problem.assemble(X);
  ASSERT_EQ(problem.factorize(), Status::kConverged);
  const Eigen::VectorXd u = problem.solve();
  // Clapeyron: with homogeneous Dirichlet data, strain energy = ½ work of the loads.
  EXPECT_NEAR(problem.strain_energy(X, u), 0.5 * problem.external_work(X, u), 1e-10 * problem.external_work(X, u));
  // The residual vanishes at free DOFs (equilibrium) and gives the reactions at Γ_u.
  const Eigen::VectorXd r = problem.residual(X, u);
  EXPECT_LE(problem.dofs().restrict(r).norm(), 1e-8 * l.norm());
  Eigen::VectorXd reaction = Eigen::VectorXd::Zero(dim);
  for (int n = 0; n < mesh.num_nodes(); ++n) reaction += r.segment(n * dim, dim);
  // Global equilibrium: the reactions balance the applied traction resultant, reaction = −A·t.
  EXPECT_LE((reaction + top_area * t).norm(), 1e-8 * top_area * t.norm());
}

TEST_P(ElasticityByElement, ShapeDerivativeKernelMatchesCentralDifferences) {
  const int dim = GetParam().dim;
  const mesh::ElementFamily family = GetParam().family;
  const auto s = make_shape(dim);
  const mesh::Mesh mesh = mesh::StructuredMesh(s, 1.0, resolution(dim, 3, family)).take_mesh();
  // A traction on the right face, which moves with α, exercises ∂l/∂α as well as ∂A/∂α.
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(dim, -1e6, 3e6);
  LinearElasticity problem(mesh, kSteel, expand_dirichlet(mesh, {{"left", {}, {}}}),
                           {{"right", t}, {"top", -t}});
  std::mt19937_64 rng{kSeed};
  std::normal_distribution<double> normal;
  Eigen::VectorXd u(mesh.num_dofs()), p(mesh.num_dofs());
  for (int i = 0; i < mesh.num_dofs(); ++i) {
    u(i) = 1e-4 * normal(rng);
    p(i) = normal(rng);
  }
  const Eigen::VectorXd alpha = curved_design(s.num_controls());
  const auto f = [&](const Eigen::VectorXd& a) { return p.dot(problem.residual(mesh.positions(a), u)); };
  const Eigen::VectorXd kernel = problem.shape_derivative(mesh.positions(alpha), u, p);
  const Eigen::VectorXd fd = frictopt::testing::central_gradient(f, alpha, 1e-5);
  const double error = (kernel - fd).norm() / fd.norm();
  std::printf("dim %d: shape-derivative kernel vs central differences: relative error %.2e\n", dim, error);
  EXPECT_LE(error, 1e-6);
  const auto ratios = frictopt::testing::taylor_ratios(f, alpha, kernel, frictopt::testing::random_direction(rng, alpha.size()), 1e-2);
  EXPECT_GT(ratios.front(), 3.0);  // second-order Taylor remainder: ratio ~4
}

TEST_P(ElasticityByElement, ResidualDirectionalDerivativeMatchesDifferencesAndTheKernel) {
  const int dim = GetParam().dim;
  const mesh::ElementFamily family = GetParam().family;
  const auto s = make_shape(dim);
  const mesh::Mesh mesh = mesh::StructuredMesh(s, 1.0, resolution(dim, 3, family)).take_mesh();
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(dim, -1e6, 3e6);
  LinearElasticity problem(mesh, kSteel, expand_dirichlet(mesh, {{"left", {}, {}}}),
                           {{"right", t}});
  std::mt19937_64 rng{kSeed};
  std::normal_distribution<double> normal;
  Eigen::VectorXd u(mesh.num_dofs()), p(mesh.num_dofs());
  for (int i = 0; i < mesh.num_dofs(); ++i) {
    u(i) = 1e-4 * normal(rng);
    p(i) = normal(rng);
  }
  const Eigen::VectorXd alpha = curved_design(s.num_controls());
  const Eigen::VectorXd h = frictopt::testing::random_direction(rng, alpha.size());
  const Eigen::VectorXd Vh = mesh.design_jacobian() * h;
  const Eigen::MatrixXd dX = Eigen::Map<const Eigen::MatrixXd>(Vh.data(), dim, mesh.num_nodes()).transpose();
  const Eigen::MatrixXd X = mesh.positions(alpha);
  const Eigen::VectorXd forward = problem.residual_derivative(X, u, dX);
  const double eps = 1e-5;
  const Eigen::VectorXd fd = (problem.residual(mesh.positions(alpha + eps * h), u) -
                              problem.residual(mesh.positions(alpha - eps * h), u)) / (2 * eps);
  EXPECT_LE((forward - fd).norm(), 1e-7 * fd.norm());
  // Forward and reverse modes agree: pᵀ(∂r/∂α h) = (∇_α pᵀr)·h.
  EXPECT_NEAR(p.dot(forward), problem.shape_derivative(X, u, p).dot(h), 1e-10 * std::abs(p.dot(forward)));
}

INSTANTIATE_TEST_SUITE_P(Dim, ElasticityByDimension, ::testing::Values(2, 3),
                         [](const auto& param_info) { return "Dim" + std::to_string(param_info.param); });
INSTANTIATE_TEST_SUITE_P(Element, ElasticityByElement,
                         ::testing::Values(ElementCase{2, mesh::ElementFamily::kTensorProduct},
                                           ElementCase{3, mesh::ElementFamily::kTensorProduct},
                                           ElementCase{2, mesh::ElementFamily::kSimplex},
                                           ElementCase{3, mesh::ElementFamily::kSimplex}),
                         [](const auto& param_info) {
                           return std::string(mesh::to_string(
                               mesh::element_kind(param_info.param.family, param_info.param.dim)));
                         });

TEST(StressRecovery, VonMisesOfUniaxialAndPureShear) {
  Eigen::Matrix<double, 6, 1> s;
  s << 100, 0, 0, 0, 0, 0;
  EXPECT_NEAR(von_mises(s), 100, 1e-12);
  s << 0, 0, 0, 50, 0, 0;
  EXPECT_NEAR(von_mises(s), std::sqrt(3.0) * 50, 1e-12);
}

TEST(Material, RejectsOutOfRangeConstantsNamingTheField) {
  IsotropicMaterial m{1e9, 0.5, PlaneModel::kPlaneStrain};
  try {
    m.validate();
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("material.poisson"), std::string::npos);
  }
  m = {-1.0, 0.3, PlaneModel::kPlaneStrain};
  EXPECT_THROW(m.validate(), InvalidInput);
  EXPECT_THROW((void)parse_plane_model("plain_strain"), InvalidInput);
}

}  // namespace
}  // namespace frictopt::fem
