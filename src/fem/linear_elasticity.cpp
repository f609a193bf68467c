// SPDX-License-Identifier: MIT
#include "frictopt/fem/linear_elasticity.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "element_kernels.hpp"
#include "frictopt/mesh/elements.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::fem {

LinearElasticity::LinearElasticity(const mesh::Mesh& mesh, const IsotropicMaterial& material,
                                   const PrescribedDofs& dirichlet, std::vector<FaceTraction> tractions,
                                   linalg::SpdSolver::Options solver, const std::vector<std::vector<int>>& ties)
    : mesh_(mesh),
      material_(material),
      dofs_(mesh.num_dofs(), dirichlet, ties),
      tractions_(std::move(tractions)),
      solver_options_(solver),
      solver_(linalg::SpdSolver::create(solver)) {
  material_.validate();
  for (std::size_t i = 0; i < tractions_.size(); ++i) {
    if (tractions_[i].traction.size() != mesh.dim())
      throw InvalidInput(fmt::format("load[{}].traction has {} entries; expected {}", i,
                                     tractions_[i].traction.size(), mesh.dim()));
    (void)mesh.boundary(tractions_[i].boundary);  // throws InvalidInput for an unknown name
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
  std::vector<int> column;
  for (int col = 0; col < n; ++col) {
    // The column of an unknown is the union over the DOFs it stands for (a tied group: every
    // plate node's neighbours, PᵀAP); rows sorted for the CSC pattern.
    const int tie = dofs_.tie_of(col);
    const std::vector<int> single{dofs_.free_dofs()[col]};
    const std::vector<int>& members = tie >= 0 ? dofs_.ties()[static_cast<std::size_t>(tie)] : single;
    column.clear();
    for (int dof : members)
      for (int neighbour : adjacency[dof / dim])
        for (int c = 0; c < dim; ++c) {
          const int row = dofs_.free_index(neighbour * dim + c);
          if (row >= 0) column.push_back(row);
        }
    std::sort(column.begin(), column.end());
    column.erase(std::unique(column.begin(), column.end()), column.end());
    inner.insert(inner.end(), column.begin(), column.end());
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
template <class Element>
typename detail::ElasticityKernel<Element>::Coordinates element_coordinates(const mesh::Connectivity& elements,
                                                                             Eigen::Index e,
                                                                             const Eigen::Ref<const Eigen::MatrixXd>& X) {
  typename detail::ElasticityKernel<Element>::Coordinates Xe;
  for (int a = 0; a < Element::kNodes; ++a) Xe.row(a) = X.row(elements(e, a));
  return Xe;
}
template <class Element>
typename detail::ElasticityKernel<Element>::Vector element_values(const mesh::Connectivity& elements, Eigen::Index e,
                                                                   const Eigen::Ref<const Eigen::VectorXd>& u) {
  constexpr int Dim = Element::kDim;
  typename detail::ElasticityKernel<Element>::Vector ue;
  for (int a = 0; a < Element::kNodes; ++a) ue.template segment<Dim>(a * Dim) = u.segment(elements(e, a) * Dim, Dim);
  return ue;
}
}  // namespace

template <class Element>
void LinearElasticity::assemble_impl(const Eigen::Ref<const Eigen::MatrixXd>& X) {
  constexpr int Dim = Element::kDim;
  using Kernel = detail::ElasticityKernel<Element>;
  const Kernel kernel{material_.lame_lambda(Dim), material_.shear_modulus()};
  const auto& elements = mesh_.elements();
  std::fill(A_.valuePtr(), A_.valuePtr() + A_.nonZeros(), 0.0);
  const Eigen::VectorXd& ud = dofs_.prescribed_values();
  const Eigen::VectorXd traction = traction_load_impl<Element>(X);
  l_ = dofs_.restrict_forces(traction);
  double* values = A_.valuePtr();
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    const typename Kernel::Matrix K = kernel.stiffness(element_coordinates<Element>(elements, e, X));
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
  mesh::with_element(mesh_.element_kind(), [&](auto element) { assemble_impl<decltype(element)>(X); });
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

template <class Element>
Eigen::VectorXd LinearElasticity::traction_load_impl(const Eigen::Ref<const Eigen::MatrixXd>& X) const {
  constexpr int Dim = Element::kDim;
  using Facet = detail::FacetKernel<Element>;
  Eigen::VectorXd l = Eigen::VectorXd::Zero(mesh_.num_dofs());
  for (const FaceTraction& load : tractions_) {
    const mesh::Connectivity& facets = mesh_.boundary(load.boundary).facets;
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
  return mesh::with_element(mesh_.element_kind(), [&](auto element) { return traction_load_impl<decltype(element)>(X); });
}

template <class Element>
Eigen::VectorXd LinearElasticity::residual_impl(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                const Eigen::Ref<const Eigen::VectorXd>& u) const {
  constexpr int Dim = Element::kDim;
  using Kernel = detail::ElasticityKernel<Element>;
  const Kernel kernel{material_.lame_lambda(Dim), material_.shear_modulus()};
  const auto& elements = mesh_.elements();
  Eigen::VectorXd r = -traction_load_impl<Element>(X);
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    const typename Kernel::Vector fe = kernel.stiffness(element_coordinates<Element>(elements, e, X)) *
                                       element_values<Element>(elements, e, u);
    for (int a = 0; a < Kernel::kNodes; ++a) r.segment(elements(e, a) * Dim, Dim) += fe.template segment<Dim>(a * Dim);
  }
  return r;
}

Eigen::VectorXd LinearElasticity::residual(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                           const Eigen::Ref<const Eigen::VectorXd>& u) const {
  return mesh::with_element(mesh_.element_kind(), [&](auto element) { return residual_impl<decltype(element)>(X, u); });
}

template <class Element>
Eigen::VectorXd LinearElasticity::coordinate_derivative_impl(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                             const Eigen::Ref<const Eigen::VectorXd>& u,
                                                             const Eigen::Ref<const Eigen::VectorXd>& p) const {
  constexpr int Dim = Element::kDim;
  using Kernel = detail::ElasticityKernel<Element>;
  using Facet = detail::FacetKernel<Element>;
  const Kernel kernel{material_.lame_lambda(Dim), material_.shear_modulus()};
  const auto& elements = mesh_.elements();
  Eigen::VectorXd g = Eigen::VectorXd::Zero(mesh_.num_dofs());
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    const typename Kernel::Coordinates ge = kernel.energy_coordinate_gradient(
        element_coordinates<Element>(elements, e, X), element_values<Element>(elements, e, u),
        element_values<Element>(elements, e, p));
    for (int a = 0; a < Kernel::kNodes; ++a) g.segment(elements(e, a) * Dim, Dim) += ge.row(a).transpose();
  }
  for (const FaceTraction& load : tractions_) {
    const mesh::Connectivity& facets = mesh_.boundary(load.boundary).facets;
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
  return mesh::with_element(mesh_.element_kind(),
                            [&](auto element) { return coordinate_derivative_impl<decltype(element)>(X, u, p); });
}

template <class Element>
Eigen::VectorXd LinearElasticity::residual_derivative_impl(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                           const Eigen::Ref<const Eigen::VectorXd>& u,
                                                           const Eigen::Ref<const Eigen::MatrixXd>& dX) const {
  constexpr int Dim = Element::kDim;
  using Kernel = detail::ElasticityKernel<Element>;
  using Facet = detail::FacetKernel<Element>;
  const Kernel kernel{material_.lame_lambda(Dim), material_.shear_modulus()};
  const auto& elements = mesh_.elements();
  Eigen::VectorXd r = Eigen::VectorXd::Zero(mesh_.num_dofs());
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    const typename Kernel::Vector df = detail::ElasticityDirectional<Element>::force_derivative(
        kernel, element_coordinates<Element>(elements, e, X), element_values<Element>(elements, e, u),
        element_coordinates<Element>(elements, e, dX));
    for (int a = 0; a < Kernel::kNodes; ++a) r.segment(elements(e, a) * Dim, Dim) += df.template segment<Dim>(a * Dim);
  }
  for (const FaceTraction& load : tractions_) {
    const mesh::Connectivity& facets = mesh_.boundary(load.boundary).facets;
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
  return mesh::with_element(mesh_.element_kind(),
                            [&](auto element) { return residual_derivative_impl<decltype(element)>(X, u, dX); });
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
