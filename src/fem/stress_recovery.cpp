// SPDX-License-Identifier: MIT
#include "frictopt/fem/stress_recovery.hpp"

#include <cmath>

#include "element_kernels.hpp"
#include "frictopt/mesh/elements.hpp"

namespace frictopt::fem {

double von_mises(const Eigen::Ref<const Eigen::Matrix<double, 6, 1>>& s) {
  const double d = (s(0) - s(1)) * (s(0) - s(1)) + (s(1) - s(2)) * (s(1) - s(2)) + (s(2) - s(0)) * (s(2) - s(0));
  return std::sqrt(0.5 * d + 3.0 * (s(3) * s(3) + s(4) * s(4) + s(5) * s(5)));
}

namespace {
template <class Element, int Dim = Element::kDim>
Eigen::Matrix<double, 6, 1> voigt6(const Eigen::Matrix<double, Dim, Dim>& H,
                                   const detail::ElasticityKernel<Element>& kernel, const IsotropicMaterial& material) {
  const Eigen::Matrix<double, Dim, Dim> s = kernel.stress(H);
  Eigen::Matrix<double, 6, 1> v = Eigen::Matrix<double, 6, 1>::Zero();
  if constexpr (Dim == 2) {
    v(0) = s(0, 0);
    v(1) = s(1, 1);
    v(2) = material.plane_model == PlaneModel::kPlaneStrain ? kernel.lambda * H.trace() : 0.0;
    v(3) = s(0, 1);
  } else {
    v << s(0, 0), s(1, 1), s(2, 2), s(0, 1), s(1, 2), s(0, 2);
  }
  return v;
}

template <class Element>
StressField recover(const mesh::Mesh& mesh, const IsotropicMaterial& material,
                    const Eigen::Ref<const Eigen::MatrixXd>& X, const Eigen::Ref<const Eigen::VectorXd>& u) {
  constexpr int Dim = Element::kDim;
  using Kernel = detail::ElasticityKernel<Element>;
  const Kernel kernel{material.lame_lambda(Dim), material.shear_modulus()};
  const auto& elements = mesh.elements();
  const auto corners = Element::corners();
  StressField out;
  out.element = Eigen::MatrixXd::Zero(elements.rows(), 6);
  out.nodal = Eigen::MatrixXd::Zero(mesh.num_nodes(), 6);
  Eigen::VectorXd count = Eigen::VectorXd::Zero(mesh.num_nodes());
  Eigen::Matrix<double, Kernel::kNodes, Dim> G;
  double det;
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    typename Kernel::Coordinates Xe;
    typename Kernel::Vector ue;
    for (int a = 0; a < Kernel::kNodes; ++a) {
      Xe.row(a) = X.row(elements(e, a));
      ue.template segment<Dim>(a * Dim) = u.segment(elements(e, a) * Dim, Dim);
    }
    Kernel::physical_gradients(Xe, Element::centre(), G, det);
    out.element.row(e) = voigt6<Element>(Kernel::gradient(ue, G), kernel, material).transpose();
    for (int a = 0; a < Kernel::kNodes; ++a) {
      Kernel::physical_gradients(Xe, corners.row(a).transpose(), G, det);
      out.nodal.row(elements(e, a)) += voigt6<Element>(Kernel::gradient(ue, G), kernel, material).transpose();
      count(elements(e, a)) += 1.0;
    }
  }
  for (int n = 0; n < mesh.num_nodes(); ++n) out.nodal.row(n) /= count(n);
  out.element_von_mises.resize(elements.rows());
  for (Eigen::Index e = 0; e < elements.rows(); ++e) out.element_von_mises(e) = von_mises(out.element.row(e).transpose());
  out.nodal_von_mises.resize(mesh.num_nodes());
  for (int n = 0; n < mesh.num_nodes(); ++n) out.nodal_von_mises(n) = von_mises(out.nodal.row(n).transpose());
  return out;
}
}  // namespace

StressField recover_stresses(const mesh::Mesh& mesh, const IsotropicMaterial& material,
                             const Eigen::Ref<const Eigen::MatrixXd>& X, const Eigen::Ref<const Eigen::VectorXd>& u) {
  return mesh::with_element(mesh.element_kind(),
                            [&](auto element) { return recover<decltype(element)>(mesh, material, X, u); });
}

}  // namespace frictopt::fem
