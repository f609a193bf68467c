// SPDX-License-Identifier: MIT
#include "frictopt/mesh/design_extension.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>

#include "frictopt/core/enum_table.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/linalg/spd_solver.hpp"
#include "frictopt/mesh/elements.hpp"

namespace frictopt::mesh {
namespace {

constexpr auto kExtensionKindNames = frictopt::detail::make_enum_table<ExtensionKind>(
    std::pair{ExtensionKind::kLaplace, "laplace"}, std::pair{ExtensionKind::kSweep, "sweep"});

// The scalar Laplace stiffness K_ab = ∫ ∇N_a·∇N_b dx on the cells (2×2(×2) Gauss), the
// extension's operator: the discrete harmonic extension of the patch motion minimizes the
// Dirichlet energy of the motion, which keeps it as smooth as the mesh allows.
template <class Element>
Eigen::SparseMatrix<double> laplace_stiffness(const Mesh& body) {
  constexpr int Dim = Element::kDim;
  constexpr int N = Element::kNodes;
  const Eigen::MatrixXd& X = body.reference_positions();
  const Connectivity& cells = body.elements();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(cells.rows()) * N * N);
  Eigen::Matrix<double, N, Dim> Xe;
  for (Eigen::Index e = 0; e < cells.rows(); ++e) {
    for (int a = 0; a < N; ++a) Xe.row(a) = X.row(cells(e, a));
    Eigen::Matrix<double, N, N> Ke = Eigen::Matrix<double, N, N>::Zero();
    for (const auto& [xi, w] : Element::quadrature()) {
      const auto G = Element::gradients(xi);
      const Eigen::Matrix<double, Dim, Dim> J = Xe.transpose() * G;
      const Eigen::Matrix<double, N, Dim> dN = G * J.inverse();
      Ke += w * std::abs(J.determinant()) * dN * dN.transpose();
    }
    for (int a = 0; a < N; ++a)
      for (int b = 0; b < N; ++b) triplets.emplace_back(cells(e, a), cells(e, b), Ke(a, b));
  }
  Eigen::SparseMatrix<double> K(body.num_nodes(), body.num_nodes());
  K.setFromTriplets(triplets.begin(), triplets.end());
  return K;
}

// φ (num_nodes × d): φ(i, k) = the normal motion of node i per unit α_k.
Eigen::MatrixXd laplace_extension(const Mesh& body, const std::vector<int>& patch_nodes,
                                  const Eigen::MatrixXd& patch_values, const std::vector<bool>& fixed) {
  const int n = body.num_nodes();
  const Eigen::Index d = patch_values.cols();
  // -1: free; >= 0: row of the prescribed values (patch) ; -2: fixed at zero.
  std::vector<int> role(static_cast<std::size_t>(n), -1);
  for (int i = 0; i < n; ++i)
    if (fixed[static_cast<std::size_t>(i)]) role[static_cast<std::size_t>(i)] = -2;
  for (std::size_t k = 0; k < patch_nodes.size(); ++k) role[static_cast<std::size_t>(patch_nodes[k])] = static_cast<int>(k);
  std::vector<int> free_index(static_cast<std::size_t>(n), -1);
  int num_free = 0;
  for (int i = 0; i < n; ++i)
    if (role[static_cast<std::size_t>(i)] == -1) free_index[static_cast<std::size_t>(i)] = num_free++;

  Eigen::MatrixXd phi = Eigen::MatrixXd::Zero(n, d);
  for (std::size_t k = 0; k < patch_nodes.size(); ++k) phi.row(patch_nodes[k]) = patch_values.row(static_cast<Eigen::Index>(k));
  if (num_free == 0) return phi;

  const Eigen::SparseMatrix<double> K =
      with_element(body.element_kind(), [&](auto element) { return laplace_stiffness<decltype(element)>(body); });
  // K_ff φ_f = −K_fp φ_p: the free block and the right-hand sides from the patch values.
  std::vector<Eigen::Triplet<double>> t;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(num_free, d);
  for (int col = 0; col < K.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, col); it; ++it) {
      const int row = static_cast<int>(it.row());
      const int fr = free_index[static_cast<std::size_t>(row)];
      if (fr < 0) continue;
      const int fc = free_index[static_cast<std::size_t>(col)];
      if (fc >= 0) {
        t.emplace_back(fr, fc, it.value());
      } else if (role[static_cast<std::size_t>(col)] >= 0) {
        rhs.row(fr) -= it.value() * patch_values.row(role[static_cast<std::size_t>(col)]);
      }
    }
  Eigen::SparseMatrix<double> K_ff(num_free, num_free);
  K_ff.setFromTriplets(t.begin(), t.end());
  const auto solver = linalg::SpdSolver::create();
  if (solver->analyze(K_ff) != Status::kConverged || solver->factorize(K_ff) != Status::kConverged)
    throw InvalidInput(fmt::format("design extension: the Laplace extension's matrix could not be factorized ({}); "
                                   "expected every part of the body connected to the patch or a fixed set",
                                   solver->message()));
  const Eigen::MatrixXd phi_free = solver->solve_many(rhs);
  for (int i = 0; i < n; ++i)
    if (free_index[static_cast<std::size_t>(i)] >= 0) phi.row(i) = phi_free.row(free_index[static_cast<std::size_t>(i)]);
  return phi;
}

}  // namespace

PlaneFrame PlaneFrame::standard(int dim) {
  PlaneFrame f;
  f.normal = Eigen::VectorXd::Unit(dim, dim - 1);
  f.tangents = Eigen::MatrixXd::Identity(dim, dim - 1);
  return f;
}

PlaneFrame PlaneFrame::from_normal(const Eigen::VectorXd& normal, const Eigen::VectorXd& first_axis) {
  const Eigen::Index dim = normal.size();
  if (dim != 2 && dim != 3) throw InvalidInput(fmt::format("foundation normal of size {}; expected 2 or 3", dim));
  if (!(normal.norm() > 0) || !normal.allFinite())
    throw InvalidInput("foundation normal is zero or not finite; expected a nonzero vector");
  PlaneFrame f;
  f.normal = normal.normalized();
  f.tangents.resize(dim, dim - 1);
  if (dim == 2) {
    f.tangents.col(0) << f.normal(1), -f.normal(0);  // e1 = n rotated by −90°: e1 = e_x for n = e_y
    return f;
  }
  if (first_axis.size() != 3) throw InvalidInput(fmt::format("foundation axis of size {}; expected 3", first_axis.size()));
  const Eigen::Vector3d n = f.normal;
  const Eigen::Vector3d e1 = Eigen::Vector3d(first_axis) - n.dot(first_axis) * n;
  if (!(e1.norm() > 1e-8 * first_axis.norm()))
    throw InvalidInput("foundation axis is parallel to the normal; expected an axis with a component in the plane");
  f.tangents.col(0) = e1.normalized();
  f.tangents.col(1) = n.cross(e1.normalized());
  return f;
}

Eigen::VectorXd PlaneFrame::plane_coordinates(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  return tangents.transpose() * x;
}

std::string_view to_string(ExtensionKind kind) { return kExtensionKindNames.name(kind); }

ExtensionKind parse_extension_kind(std::string_view name) {
  if (const auto kind = kExtensionKindNames.find(name)) return *kind;
  throw InvalidInput(fmt::format("design extension '{}'; expected one of {}", name, kExtensionKindNames.spellings()));
}

PatchChart patch_chart(const Mesh& body, const std::string& patch, const PlaneFrame& frame) {
  const BoundarySet& set = body.boundary(patch);
  const int dim = body.dim();
  Eigen::VectorXd lo = Eigen::VectorXd::Constant(dim - 1, INFINITY), hi = Eigen::VectorXd::Constant(dim - 1, -INFINITY);
  for (int node : set.nodes) {
    const Eigen::VectorXd x = frame.plane_coordinates(body.reference_positions().row(node).transpose());
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  PatchChart chart{lo, hi - lo};
  for (int c = 0; c < dim - 1; ++c)
    if (set.nodes.empty() || !(chart.extents(c) > 0))
      throw InvalidInput(fmt::format("design patch '{}' has {} along tangent axis {} of the foundation; expected a "
                                     "patch that faces the foundation (an extent > 0 in every in-plane direction)",
                                     patch, set.nodes.empty() ? "no nodes" : "zero extent", c + 1));
  return chart;
}

Mesh with_design_motion(const Mesh& body, const shape::BezierShape& shape, const DesignMotion& motion) {
  const int dim = body.dim();
  const PlaneFrame frame = motion.frame.normal.size() == 0 ? PlaneFrame::standard(dim) : motion.frame;
  if (frame.dim() != dim || shape.dim() != dim)
    throw InvalidInput(fmt::format("design patch '{}': a {}D frame and a {}D Bézier shape for a {}D mesh", motion.patch,
                                   frame.dim(), shape.dim(), dim));
  const PatchChart chart = patch_chart(body, motion.patch, frame);
  const auto shape_extents = shape.extents();
  for (int c = 0; c < dim - 1; ++c)
    if (std::abs(shape_extents[static_cast<std::size_t>(c)] - chart.extents(c)) > 1e-12 * chart.extents(c))
      throw InvalidInput(fmt::format("design patch '{}': the Bézier shape spans {} m along axis {}; expected the "
                                     "patch's extent {} m",
                                     motion.patch, shape_extents[static_cast<std::size_t>(c)], c + 1, chart.extents(c)));
  const Eigen::MatrixXd& X = body.reference_positions();
  // The Bézier parameter of a node, clamped to the chart (nodes off the patch, for kSweep).
  const auto basis_at = [&](int node) {
    Eigen::VectorXd s = frame.plane_coordinates(X.row(node).transpose()) - chart.origin;
    s = s.cwiseMax(0.0).cwiseMin(chart.extents);
    return shape.basis(s);
  };
  const Eigen::Index d = shape.num_controls();
  const std::vector<int>& patch_nodes = body.boundary(motion.patch).nodes;

  Eigen::MatrixXd phi;  // normal motion per unit α_k, num_nodes × d
  if (motion.extension == ExtensionKind::kSweep) {
    const Eigen::VectorXd t = X * frame.normal;  // height of every node above the plane n·x = 0
    double t_patch = INFINITY;
    for (int node : patch_nodes) t_patch = std::min(t_patch, t(node));
    const double t_top = t.maxCoeff();
    if (!(t_top > t_patch))
      throw InvalidInput(fmt::format("design patch '{}': the body has no height above the patch along the foundation "
                                     "normal; expected extension = \"laplace\"",
                                     motion.patch));
    phi.resize(body.num_nodes(), d);
    for (int i = 0; i < body.num_nodes(); ++i) {
      const double weight = std::clamp((t_top - t(i)) / (t_top - t_patch), 0.0, 1.0);
      phi.row(i) = weight * basis_at(i).transpose();
    }
    for (int node : patch_nodes) phi.row(node) = basis_at(node).transpose();
  } else {
    std::vector<bool> fixed(static_cast<std::size_t>(body.num_nodes()), false);
    for (const std::string& name : motion.fixed)
      for (int node : body.boundary(name).nodes) fixed[static_cast<std::size_t>(node)] = true;
    Eigen::MatrixXd patch_values(static_cast<Eigen::Index>(patch_nodes.size()), d);
    for (std::size_t k = 0; k < patch_nodes.size(); ++k)
      patch_values.row(static_cast<Eigen::Index>(k)) = basis_at(patch_nodes[k]).transpose();
    phi = laplace_extension(body, patch_nodes, patch_values, fixed);
  }

  // V((node, c), k) = n_c φ(node, k): every node moves along the foundation normal.
  std::vector<Eigen::Triplet<double>> triplets;
  for (int i = 0; i < body.num_nodes(); ++i)
    for (Eigen::Index k = 0; k < d; ++k) {
      if (phi(i, k) == 0.0) continue;
      for (int c = 0; c < dim; ++c)
        if (frame.normal(c) != 0.0) triplets.emplace_back(i * dim + c, k, frame.normal(c) * phi(i, k));
    }
  Eigen::SparseMatrix<double> V(body.num_dofs(), d);
  V.setFromTriplets(triplets.begin(), triplets.end());
  return body.with_design_jacobian(std::move(V));
}

}  // namespace frictopt::mesh
