// SPDX-License-Identifier: MIT
#include "frictopt/fem/linear_elasticity.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "element_kernels.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::fem {

LinearElasticity::LinearElasticity(const mesh::StructuredMesh& mesh, const IsotropicMaterial& material,
                                   const PrescribedDofs& dirichlet, std::vector<FaceTraction> tractions,
                                   linalg::SpdSolver::Options solver)
    : mesh_(mesh),
      material_(material),
      dofs_(mesh.num_dofs(), dirichlet),
      tractions_(std::move(tractions)),
      solver_options_(solver),
      solver_(linalg::SpdSolver::create(solver)) {
  material_.validate();
  for (std::size_t i = 0; i < tractions_.size(); ++i) {
    if (tractions_[i].traction.size() != mesh.dim())
      throw InvalidInput(fmt::format("load[{}].traction has {} entries; expected {}", i,
                                     tractions_[i].traction.size(), mesh.dim()));
    (void)mesh.face_facets(tractions_[i].face);  // throws for front/back in 2D
  }
  build_pattern();
}

void LinearElasticity::build_pattern() {
  // Column-wise CSC pattern from node adjacency (nodes sharing an element), built directly
  // rather than through triplets: at 200k DOFs the triplet list would need ~0.6 GB.
  const int dim = mesh_.dim(), nodes = mesh_.num_nodes();
  const auto& elements = mesh_.elements();
  std::vector<std::vector<int>> adjacency(nodes);
  for (Eigen::Index e = 0; e < elements.rows(); ++e)
    for (Eigen::Index a = 0; a < elements.cols(); ++a)
      for (Eigen::Index b = 0; b < elements.cols(); ++b) adjacency[elements(e, a)].push_back(elements(e, b));
  for (auto& list : adjacency) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  const int n = dofs_.num_free();
  std::vector<int> outer(n + 1, 0);
  std::vector<int> inner;
  for (int col = 0; col < n; ++col) {
    const int dof = dofs_.free_dofs()[col];
    for (int neighbour : adjacency[dof / dim])
      for (int c = 0; c < dim; ++c) {
        const int row = dofs_.free_index(neighbour * dim + c);
        if (row >= 0) inner.push_back(row);
      }
    outer[col + 1] = static_cast<int>(inner.size());
  }
  A_ = Eigen::SparseMatrix<double>(n, n);
  A_.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), A_.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), A_.innerIndexPtr());
  std::fill(A_.valuePtr(), A_.valuePtr() + inner.size(), 0.0);

  const int ndof_e = static_cast<int>(elements.cols()) * dim;
  scatter_.assign(static_cast<std::size_t>(elements.rows()) * ndof_e * ndof_e, -1);
  for (Eigen::Index e = 0; e < elements.rows(); ++e)
    for (int i = 0; i < ndof_e; ++i) {
      const int row = dofs_.free_index(elements(e, i / dim) * dim + i % dim);
      if (row < 0) continue;
      for (int j = 0; j < ndof_e; ++j) {
        const int col = dofs_.free_index(elements(e, j / dim) * dim + j % dim);
        if (col < 0) continue;
        const int* begin = A_.innerIndexPtr() + outer[col];
        const int* end = A_.innerIndexPtr() + outer[col + 1];
        const int* hit = std::lower_bound(begin, end, row);
        FRICTOPT_ASSERT(hit != end && *hit == row, "pattern misses an element entry");
        scatter_[(static_cast<std::size_t>(e) * ndof_e + i) * ndof_e + j] = static_cast<int>(hit - A_.innerIndexPtr());
      }
    }
  l_ = Eigen::VectorXd::Zero(n);
}

namespace {
template <int Dim>
typename detail::ElasticityKernel<Dim>::Coordinates element_coordinates(const mesh::Connectivity& elements,
                                                                         Eigen::Index e,
                                                                         const Eigen::Ref<const Eigen::MatrixXd>& X) {
  typename detail::ElasticityKernel<Dim>::Coordinates Xe;
  for (int a = 0; a < detail::ElasticityKernel<Dim>::kNodes; ++a) Xe.row(a) = X.row(elements(e, a));
  return Xe;
}
template <int Dim>
typename detail::ElasticityKernel<Dim>::Vector element_values(const mesh::Connectivity& elements, Eigen::Index e,
                                                               const Eigen::Ref<const Eigen::VectorXd>& u) {
  typename detail::ElasticityKernel<Dim>::Vector ue;
  for (int a = 0; a < detail::ElasticityKernel<Dim>::kNodes; ++a)
    ue.template segment<Dim>(a * Dim) = u.segment(elements(e, a) * Dim, Dim);
  return ue;
}
}  // namespace

template <int Dim>
void LinearElasticity::assemble_impl(const Eigen::Ref<const Eigen::MatrixXd>& X) {
  using Kernel = detail::ElasticityKernel<Dim>;
  const Kernel kernel{material_.lame_lambda(Dim), material_.shear_modulus()};
  const auto& elements = mesh_.elements();
  std::fill(A_.valuePtr(), A_.valuePtr() + A_.nonZeros(), 0.0);
  const Eigen::VectorXd& ud = dofs_.prescribed_values();
  const Eigen::VectorXd traction = traction_load_impl<Dim>(X);
  l_ = dofs_.restrict(traction);
  double* values = A_.valuePtr();
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    const typename Kernel::Matrix K = kernel.stiffness(element_coordinates<Dim>(elements, e, X));
    const int* map = scatter_.data() + static_cast<std::size_t>(e) * Kernel::kDofs * Kernel::kDofs;
    for (int i = 0; i < Kernel::kDofs; ++i) {
      const int dof_i = elements(e, i / Dim) * Dim + i % Dim;
      const int row = dofs_.free_index(dof_i);
      if (row < 0) continue;
      for (int j = 0; j < Kernel::kDofs; ++j) {
        const int slot = map[i * Kernel::kDofs + j];
        if (slot >= 0) {
          values[slot] += K(i, j);
        } else {
          // Lifting of a prescribed value: l_f −= A_fd u_d.
          const int dof_j = elements(e, j / Dim) * Dim + j % Dim;
          l_(row) -= K(i, j) * ud(dof_j);
        }
      }
    }
  }
}

void LinearElasticity::assemble(const Eigen::Ref<const Eigen::MatrixXd>& X) {
  FRICTOPT_ASSERT(X.rows() == mesh_.num_nodes() && X.cols() == mesh_.dim(), "positions shape");
  if (mesh_.dim() == 2)
    assemble_impl<2>(X);
  else
    assemble_impl<3>(X);
}

void LinearElasticity::set_trailing_dofs(std::vector<int> free_indices) {
  trailing_ = std::move(free_indices);
  solver_ = linalg::SpdSolver::create(solver_options_);  // the next factorize() analyzes with this ordering
}

Status LinearElasticity::factorize() {
  if (!solver_->analyzed()) {
    const Status analysis = trailing_.empty() ? solver_->analyze(A_) : solver_->analyze(A_, trailing_);
    if (analysis != Status::kConverged) return analysis;
  }
  return solver_->factorize(A_);
}

Eigen::VectorXd LinearElasticity::solve() const { return dofs_.expand(solver_->solve(l_)); }

template <int Dim>
Eigen::VectorXd LinearElasticity::traction_load_impl(const Eigen::Ref<const Eigen::MatrixXd>& X) const {
  using Facet = detail::FacetKernel<Dim>;
  Eigen::VectorXd l = Eigen::VectorXd::Zero(mesh_.num_dofs());
  for (const FaceTraction& load : tractions_) {
    const mesh::Connectivity facets = mesh_.face_facets(load.face);
    const Eigen::Matrix<double, Dim, 1> t = load.traction;
    for (Eigen::Index f = 0; f < facets.rows(); ++f) {
      typename Facet::Coordinates Xf;
      for (int a = 0; a < Facet::kNodes; ++a) Xf.row(a) = X.row(facets(f, a));
      const typename Facet::Coordinates forces = Facet::load(Xf, t);
      for (int a = 0; a < Facet::kNodes; ++a) l.segment(facets(f, a) * Dim, Dim) += forces.row(a).transpose();
    }
  }
  return l;
}

Eigen::VectorXd LinearElasticity::traction_load(const Eigen::Ref<const Eigen::MatrixXd>& X) const {
  return mesh_.dim() == 2 ? traction_load_impl<2>(X) : traction_load_impl<3>(X);
}

template <int Dim>
Eigen::VectorXd LinearElasticity::residual_impl(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                const Eigen::Ref<const Eigen::VectorXd>& u) const {
  using Kernel = detail::ElasticityKernel<Dim>;
  const Kernel kernel{material_.lame_lambda(Dim), material_.shear_modulus()};
  const auto& elements = mesh_.elements();
  Eigen::VectorXd r = -traction_load_impl<Dim>(X);
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    const typename Kernel::Vector fe = kernel.stiffness(element_coordinates<Dim>(elements, e, X)) *
                                       element_values<Dim>(elements, e, u);
    for (int a = 0; a < Kernel::kNodes; ++a) r.segment(elements(e, a) * Dim, Dim) += fe.template segment<Dim>(a * Dim);
  }
  return r;
}

Eigen::VectorXd LinearElasticity::residual(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                           const Eigen::Ref<const Eigen::VectorXd>& u) const {
  return mesh_.dim() == 2 ? residual_impl<2>(X, u) : residual_impl<3>(X, u);
}

template <int Dim>
Eigen::VectorXd LinearElasticity::coordinate_derivative_impl(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                             const Eigen::Ref<const Eigen::VectorXd>& u,
                                                             const Eigen::Ref<const Eigen::VectorXd>& p) const {
  using Kernel = detail::ElasticityKernel<Dim>;
  using Facet = detail::FacetKernel<Dim>;
  const Kernel kernel{material_.lame_lambda(Dim), material_.shear_modulus()};
  const auto& elements = mesh_.elements();
  Eigen::VectorXd g = Eigen::VectorXd::Zero(mesh_.num_dofs());
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    const typename Kernel::Coordinates ge = kernel.energy_coordinate_gradient(
        element_coordinates<Dim>(elements, e, X), element_values<Dim>(elements, e, u),
        element_values<Dim>(elements, e, p));
    for (int a = 0; a < Kernel::kNodes; ++a) g.segment(elements(e, a) * Dim, Dim) += ge.row(a).transpose();
  }
  for (const FaceTraction& load : tractions_) {
    const mesh::Connectivity facets = mesh_.face_facets(load.face);
    const Eigen::Matrix<double, Dim, 1> t = load.traction;
    for (Eigen::Index f = 0; f < facets.rows(); ++f) {
      typename Facet::Coordinates Xf, pf;
      for (int a = 0; a < Facet::kNodes; ++a) {
        Xf.row(a) = X.row(facets(f, a));
        pf.row(a) = p.segment(facets(f, a) * Dim, Dim).transpose();
      }
      const typename Facet::Coordinates gf = Facet::load_coordinate_gradient(Xf, t, pf);
      for (int a = 0; a < Facet::kNodes; ++a) g.segment(facets(f, a) * Dim, Dim) -= gf.row(a).transpose();
    }
  }
  return g;
}

Eigen::VectorXd LinearElasticity::coordinate_derivative(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                        const Eigen::Ref<const Eigen::VectorXd>& u,
                                                        const Eigen::Ref<const Eigen::VectorXd>& p) const {
  FRICTOPT_ASSERT(u.size() == mesh_.num_dofs() && p.size() == mesh_.num_dofs(), "full vectors expected");
  return mesh_.dim() == 2 ? coordinate_derivative_impl<2>(X, u, p) : coordinate_derivative_impl<3>(X, u, p);
}

template <int Dim>
Eigen::VectorXd LinearElasticity::residual_derivative_impl(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                           const Eigen::Ref<const Eigen::VectorXd>& u,
                                                           const Eigen::Ref<const Eigen::MatrixXd>& dX) const {
  using Kernel = detail::ElasticityKernel<Dim>;
  using Facet = detail::FacetKernel<Dim>;
  const Kernel kernel{material_.lame_lambda(Dim), material_.shear_modulus()};
  const auto& elements = mesh_.elements();
  Eigen::VectorXd r = Eigen::VectorXd::Zero(mesh_.num_dofs());
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    const typename Kernel::Vector df = detail::ElasticityDirectional<Dim>::force_derivative(
        kernel, element_coordinates<Dim>(elements, e, X), element_values<Dim>(elements, e, u),
        element_coordinates<Dim>(elements, e, dX));
    for (int a = 0; a < Kernel::kNodes; ++a) r.segment(elements(e, a) * Dim, Dim) += df.template segment<Dim>(a * Dim);
  }
  for (const FaceTraction& load : tractions_) {
    const mesh::Connectivity facets = mesh_.face_facets(load.face);
    const Eigen::Matrix<double, Dim, 1> t = load.traction;
    for (Eigen::Index f = 0; f < facets.rows(); ++f) {
      typename Facet::Coordinates Xf, dXf;
      for (int a = 0; a < Facet::kNodes; ++a) {
        Xf.row(a) = X.row(facets(f, a));
        dXf.row(a) = dX.row(facets(f, a));
      }
      const typename Facet::Coordinates dl = Facet::load_derivative(Xf, t, dXf);
      for (int a = 0; a < Facet::kNodes; ++a) r.segment(facets(f, a) * Dim, Dim) -= dl.row(a).transpose();
    }
  }
  return r;
}

Eigen::VectorXd LinearElasticity::residual_derivative(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                      const Eigen::Ref<const Eigen::VectorXd>& u,
                                                      const Eigen::Ref<const Eigen::MatrixXd>& dX) const {
  FRICTOPT_ASSERT(dX.rows() == X.rows() && dX.cols() == X.cols(), "node motion shape");
  return mesh_.dim() == 2 ? residual_derivative_impl<2>(X, u, dX) : residual_derivative_impl<3>(X, u, dX);
}

Eigen::VectorXd LinearElasticity::shape_derivative(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                   const Eigen::Ref<const Eigen::VectorXd>& u,
                                                   const Eigen::Ref<const Eigen::VectorXd>& p) const {
  return mesh_.design_jacobian().transpose() * coordinate_derivative(X, u, p);
}

double LinearElasticity::strain_energy(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                       const Eigen::Ref<const Eigen::VectorXd>& u) const {
  return 0.5 * u.dot(residual(X, u) + traction_load(X));
}

double LinearElasticity::external_work(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                       const Eigen::Ref<const Eigen::VectorXd>& u) const {
  return traction_load(X).dot(u);
}

}  // namespace frictopt::fem
