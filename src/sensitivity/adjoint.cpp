// SPDX-License-Identifier: MIT
#include "frictopt/sensitivity/adjoint.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <chrono>

#include "frictopt/core/error.hpp"
#include "friction_geometry.hpp"
#include "frictopt/linalg/dense_blas.hpp"
#include "frictopt/sensitivity/parameter_sensitivity.hpp"

namespace frictopt::sensitivity {
namespace {

// max_c |v_c| over the first n (1 or 2) components; a loop rather than v.head(n) because GCC 12
// reports a false -Warray-bounds for dynamic heads of fixed-size vectors.
double max_abs(const Eigen::Vector2d& v, int n) { return n == 1 ? std::abs(v(0)) : std::max(std::abs(v(0)), std::abs(v(1))); }

}  // namespace

PieceLinearization linearize_piece(const Piece& piece, const contact::FrictionLaw& law,
                                   const contact::ContactState& state) {
  const int dim = state.dim;
  const Eigen::Index p = state.num_nodes();
  const Eigen::Index m = dim * p;
  FRICTOPT_ASSERT(static_cast<Eigen::Index>(piece.nodes.size()) == p, "piece size");
  std::vector<Eigen::Triplet<double>> s, cz;
  PieceLinearization out;
  const auto vertices = law.vertices();
  double residual = 0.0;
  const double force_scale = std::max(state.scales.force, 1e-300) / 1e-8;  // ≈ Λ (scales = ε_cl·Λ)
  const double disp_scale = std::max(state.scales.displacement, 1e-300) / 1e-8;
  for (Eigen::Index i = 0; i < p; ++i) {
    const NodePiece& node = piece.nodes[static_cast<std::size_t>(i)];
    const Eigen::Index base = dim * i, normal = base + dim - 1;
    const Eigen::Vector2d q = state.q(i), ut = state.u_t(i);
    const double lambda = state.lambda(i);
    // Normal row.
    if (node.normal == NormalBranch::kGapClosed) {
      s.emplace_back(normal, normal, 1.0);
      out.gap_rows.push_back(normal);
      residual = std::max(residual, std::abs(state.normal_gap(i)) / disp_scale);
    } else {
      cz.emplace_back(normal, normal, 1.0);
      residual = std::max(residual, std::abs(lambda) / force_scale);
    }
    // Tangential rows: unknown q_c is z(base + c); (G u)_c = −u_t,c.
    const int nt = dim - 1;
    switch (node.tangential) {
      case TangentialBranch::kStick:
        for (int c = 0; c < nt; ++c) s.emplace_back(base + c, base + c, -1.0);  // u_t,c = −(Gu)_c = 0
        residual = std::max(residual, max_abs(ut, nt) / disp_scale);
        break;
      case TangentialBranch::kVertexSlip: {
        const Eigen::Vector2d& w = vertices[static_cast<std::size_t>(node.index)];
        for (int c = 0; c < nt; ++c) {
          cz.emplace_back(base + c, base + c, 1.0);
          cz.emplace_back(base + c, normal, -w(c));
        }
        residual = std::max(residual, max_abs(q - lambda * w, nt) / force_scale);
        break;
      }
      case TangentialBranch::kRaySlip: {
        FRICTOPT_ASSERT(dim == 3, "ray slip exists in 3D only");
        const std::size_t n = vertices.size();
        const Eigen::Vector2d& wj = vertices[static_cast<std::size_t>(node.index)];
        const Eigen::Vector2d d = vertices[(static_cast<std::size_t>(node.index) + 1) % n] - wj;
        // (i) d × q − λ d × w_j = 0: q on the edge's line.
        cz.emplace_back(base, base, -d(1));
        cz.emplace_back(base, base + 1, d(0));
        cz.emplace_back(base, normal, -detail::cross(d, wj));
        // (ii) ⟨d, u_t⟩ = 0: u_t on the edge's normal ray; u_t = −(Gu)_t.
        s.emplace_back(base + 1, base, -d(0));
        s.emplace_back(base + 1, base + 1, -d(1));
        residual = std::max(residual, std::abs(detail::cross(d, q - lambda * wj)) / (d.norm() * force_scale));
        residual = std::max(residual, std::abs(d.dot(ut)) / (d.norm() * disp_scale));
        break;
      }
      case TangentialBranch::kSmoothSlip: {
        // q − λ w(u_t) = 0; δ: δq − w δλ − λ Dw δu_t, with δu_t = −(G δu)_t.
        const Eigen::Vector2d w = law.exposed_point(ut);
        const Eigen::Matrix2d Dw = law.exposed_point_jacobian(ut);
        for (int c = 0; c < 2; ++c) {
          cz.emplace_back(base + c, base + c, 1.0);
          cz.emplace_back(base + c, normal, -w(c));
          for (int k = 0; k < 2; ++k) s.emplace_back(base + c, base + k, lambda * Dw(c, k));
        }
        residual = std::max(residual, max_abs(q - lambda * w, 2) / force_scale);
        break;
      }
      case TangentialBranch::kZeroFriction:
        for (int c = 0; c < nt; ++c) cz.emplace_back(base + c, base + c, 1.0);
        residual = std::max(residual, max_abs(q, nt) / force_scale);
        break;
    }
  }
  out.S.resize(m, m);
  out.S.setFromTriplets(s.begin(), s.end());
  out.Cz.resize(m, m);
  out.Cz.setFromTriplets(cz.begin(), cz.end());
  out.relative_residual = residual;
  return out;
}

std::string AdjointSensitivity::Summary::brief_report() const {
  return fmt::format("adjoint: {} ({}); rcond {:.2e}, relative residual {:.2e}, piece residual {:.2e}, {:.3f} s",
                     to_string(status), message, reciprocal_condition, relative_residual, piece_residual, time_seconds);
}

void AdjointOptions::validate() const {
  if (!(singular_reciprocal_condition >= 0.0 && singular_reciprocal_condition < 1.0))
    throw InvalidInput(fmt::format("AdjointSensitivity::Options::singular_reciprocal_condition = {}; expected in [0, 1)",
                                   singular_reciprocal_condition));
}

AdjointSensitivity::AdjointSensitivity(const fem::LinearElasticity& fem, const contact::ContactBoundary& boundary,
                                       Eigen::MatrixXd gap_matrix, contact::FrictionLaw law, Options options)
    : fem_(fem), boundary_(boundary), gap_matrix_(std::move(gap_matrix)), law_(std::move(law)), options_(options) {
  options_.validate();
  if (gap_matrix_.rows() != boundary_.num_nodes())
    throw InvalidInput(fmt::format("AdjointSensitivity: gap matrix has {} rows; expected {} (one per contact node)",
                                   gap_matrix_.rows(), boundary_.num_nodes()));
}

namespace {

// The contact rows split into "identity" rows (z_k = 0 only: C_z row = e_k, S row empty) and
// the active rest A; R = z-indices not fixed by identity rows; T = z-indices S acts on.
// Then the contact-sized systems reduce to K[R, A] with M needed only on R × T (the
// elimination of the trivially fixed unknowns behind the thesis' V4.4.1,
// docs/theory/sensitivity.md §5, written for the dual variables).
struct Reduction {
  std::vector<Eigen::Index> active_rows;  // A
  std::vector<Eigen::Index> free_z;       // R
  std::vector<Eigen::Index> touched_z;    // T
};

Reduction reduce(const PieceLinearization& lin) {
  const Eigen::Index m = lin.S.rows();
  const Eigen::SparseMatrix<double, Eigen::RowMajor> S = lin.S, Cz = lin.Cz;
  std::vector<char> fixed(static_cast<std::size_t>(m), 0), touched(static_cast<std::size_t>(m), 0);
  Reduction r;
  for (Eigen::Index e = 0; e < m; ++e) {
    bool s_empty = true;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(S, e); it; ++it)
      if (it.value() != 0.0) s_empty = false;
    Eigen::Index unit = -1;
    int nonzeros = 0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Cz, e); it; ++it)
      if (it.value() != 0.0) {
        ++nonzeros;
        if (it.value() == 1.0) unit = it.col();
      }
    if (s_empty && nonzeros == 1 && unit >= 0 && !fixed[static_cast<std::size_t>(unit)]) {
      fixed[static_cast<std::size_t>(unit)] = 1;
      continue;
    }
    r.active_rows.push_back(e);
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(S, e); it; ++it)
      touched[static_cast<std::size_t>(it.col())] = 1;
  }
  for (Eigen::Index k = 0; k < m; ++k) {
    if (!fixed[static_cast<std::size_t>(k)]) r.free_z.push_back(k);
    if (touched[static_cast<std::size_t>(k)]) r.touched_z.push_back(k);
  }
  FRICTOPT_ASSERT(r.free_z.size() == r.active_rows.size(), "reduction must stay square");
  return r;
}

// The rows × cols block of a sparse matrix, kept sparse: S has at most two entries per row,
// so products with the dense Delassus block cost |R|·nnz, not the |R|·|T|·|A| of a dense GEMM.
Eigen::SparseMatrix<double> sparse_block(const Eigen::SparseMatrix<double>& A, const std::vector<Eigen::Index>& rows,
                                         const std::vector<Eigen::Index>& cols) {
  std::vector<Eigen::Index> col_position(static_cast<std::size_t>(A.cols()), -1);
  for (std::size_t j = 0; j < cols.size(); ++j) col_position[static_cast<std::size_t>(cols[j])] = static_cast<Eigen::Index>(j);
  std::vector<Eigen::Index> row_position(static_cast<std::size_t>(A.rows()), -1);
  for (std::size_t i = 0; i < rows.size(); ++i) row_position[static_cast<std::size_t>(rows[i])] = static_cast<Eigen::Index>(i);
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index c = 0; c < A.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      const Eigen::Index i = row_position[static_cast<std::size_t>(it.row())], j = col_position[static_cast<std::size_t>(c)];
      if (i >= 0 && j >= 0) entries.emplace_back(i, j, it.value());
    }
  Eigen::SparseMatrix<double> out(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
  out.setFromTriplets(entries.begin(), entries.end());
  return out;
}

// A floating body's free modes R (full DOF vectors) and W = G R (m × r); throws for free
// rotations, whose R changes with the design (docs/theory/loading-plate.md §3).
struct FloatingModes {
  const Eigen::MatrixXd* R = nullptr;
  Eigen::MatrixXd W;
  Eigen::Index size() const { return R ? R->cols() : 0; }
};

FloatingModes floating_modes(const fem::LinearElasticity& fem, const contact::ContactBoundary& boundary,
                             const char* what) {
  FloatingModes out;
  const Eigen::MatrixXd& R = fem.free_modes();
  if (R.cols() == 0) return out;
  if (!fem.free_modes_are_translations())
    throw InvalidInput(fmt::format(
        "{}: the body floats with {} free rigid-body mode{} that include a rotation (held only by contact and "
        "friction); sensitivities of such a body are not available (the rotation's modes change with the design); "
        "expected Dirichlet conditions or loading plates that leave at most translations free "
        "(docs/theory/loading-plate.md §3)",
        what, R.cols(), R.cols() == 1 ? "" : "s"));
  out.R = &R;
  out.W.resize(boundary.num_unknowns(), R.cols());
  for (Eigen::Index j = 0; j < R.cols(); ++j) out.W.col(j) = boundary.times(fem.dofs().restrict(R.col(j)));
  return out;
}

// The scale σ of the border: the largest |entry| of the piece's M block (displacement per force),
// so that the border W (of order 1/√p) enters the columns of stick and gap rows at the size of
// their M entries; with σ = 1 those columns are dominated by the border and the LU sees them as
// nearly dependent (measured: rcond 1e-18 for a body floating in x, y, z with 12 stick nodes).
// 1 when the piece has no M block.
double border_scale(const Eigen::MatrixXd& MS) {
  const double k = MS.size() ? MS.cwiseAbs().maxCoeff() : 0.0;
  return k > 0.0 ? k : 1.0;
}

}  // namespace

AdjointSensitivity::Result AdjointSensitivity::subgradient(const Piece& piece, const contact::DelassusMatrix& delassus,
                                                           const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                           const Eigen::Ref<const Eigen::VectorXd>& u,
                                                           const contact::ContactState& state,
                                                           const CostPartials& partials) const {
  const auto start = std::chrono::steady_clock::now();
  const fem::DofMap& dofs = fem_.dofs();
  const linalg::SpdSolver& cholesky = fem_.factorization();
  const Eigen::Index m = boundary_.num_unknowns();
  FRICTOPT_ASSERT(delassus.size() == m, "Delassus size");
  Result result;

  const PieceLinearization lin = linearize_piece(piece, law_, state);
  const Reduction red = reduce(lin);
  const Eigen::VectorXd gu = dofs.restrict_forces(partials.d_displacement);
  const Eigen::VectorXd gz = partials.d_contact.size() ? partials.d_contact : Eigen::VectorXd::Zero(m);

  // Contact-sized system (M Sᵀ + C_zᵀ) ψ_z = −g_z − G A⁻¹ g_u, reduced to rows R, columns A.
  const Eigen::VectorXd Ainv_gu = cholesky.solve(gu);
  const Eigen::VectorXd rhs = -gz - boundary_.times(Ainv_gu);
  const Eigen::SparseMatrix<double> St = sparse_block(lin.S, red.active_rows, red.touched_z).transpose();  // T × A
  Eigen::MatrixXd K = Eigen::MatrixXd(sparse_block(lin.Cz, red.active_rows, red.free_z).transpose());   // R × A
  Eigen::MatrixXd MS;  // the M part of K (its scale sets the floating border's)
  if (!red.touched_z.empty()) {
    MS = delassus.block(red.free_z, red.touched_z) * St;
    K += MS;
  }
  Eigen::VectorXd r(static_cast<Eigen::Index>(red.free_z.size()));
  for (std::size_t i = 0; i < red.free_z.size(); ++i) r(static_cast<Eigen::Index>(i)) = rhs(red.free_z[i]);
  const FloatingModes floating = floating_modes(fem_, boundary_, "subgradient");
  const Eigen::Index nr = floating.size();
  double border_sigma = 1.0;
  if (nr > 0) {
    // Bordered by the equilibrium rows (class comment): columns W[R, :], rows (S_AT W_T)ᵀ, both
    // scaled by σ (the scale of K) so that the LU's condition estimate compares like with like;
    // ψ_β = σ × the solved border unknowns.
    const Eigen::Index na = K.rows();
    const double sigma = border_scale(MS);
    Eigen::MatrixXd Kb = Eigen::MatrixXd::Zero(na + nr, na + nr);
    Kb.topLeftCorner(na, na) = K;
    for (std::size_t i = 0; i < red.free_z.size(); ++i)
      Kb.block(static_cast<Eigen::Index>(i), na, 1, nr) = sigma * floating.W.row(red.free_z[i]);
    const Eigen::MatrixXd SW = lin.S * floating.W;  // m × r
    for (std::size_t a = 0; a < red.active_rows.size(); ++a)
      Kb.block(na, static_cast<Eigen::Index>(a), nr, 1) = sigma * SW.row(red.active_rows[a]).transpose();
    Eigen::VectorXd rb(na + nr);
    rb.head(na) = r;
    rb.tail(nr) = -sigma * (floating.R->transpose() * partials.d_displacement);
    border_sigma = sigma;
    K = std::move(Kb);
    r = std::move(rb);
  }
  Eigen::VectorXd psi_active;
  // An exactly singular K (lu_solve false) has rcond 0 and fails the kSingular test below.
  if (!linalg::blas::lu_solve(K, r, psi_active, result.summary.reciprocal_condition))
    result.summary.reciprocal_condition = 0.0;
  result.summary.relative_residual = K.size() ? (K * psi_active - r).norm() / std::max(r.norm(), 1e-300) : 0.0;
  result.summary.piece_residual = lin.relative_residual;
  // ψ on the identity rows is not needed: their rows of S are empty, they carry no gap term
  // and do not depend on α or μ.
  result.psi_z = Eigen::VectorXd::Zero(m);
  for (std::size_t i = 0; i < red.active_rows.size(); ++i) result.psi_z(red.active_rows[i]) = psi_active(static_cast<Eigen::Index>(i));

  // ψ_u = −A⁻¹(g_u + Gᵀ Sᵀ ψ_z) (floating: A_F⁺, and − R ψ_β).
  Eigen::VectorXd w = gu;
  boundary_.add_transpose_times(lin.S.transpose() * result.psi_z, w);
  result.psi_full = dofs.expand_homogeneous(-cholesky.solve(w));
  if (nr > 0) result.psi_full -= *floating.R * (border_sigma * psi_active.tail(nr));
  result.psi_u = dofs.restrict(result.psi_full);

  // ξ = ∇_α J + ∇_α[ψ_uᵀ(A u − l)] + Σ_gap ψ_z,r B̃_node.
  const Eigen::VectorXd& psi_full = result.psi_full;
  result.subgradient = fem_.shape_derivative(X, u, psi_full);
  if (partials.d_alpha.size()) result.subgradient += partials.d_alpha;
  const int dim = boundary_.dim();
  for (Eigen::Index row : lin.gap_rows) result.subgradient += result.psi_z(row) * gap_matrix_.row(row / dim).transpose();
  // ∂Θ/∂p = (∂ contact rows/∂p)ᵀ ψ_z: the costs do not depend on μ, the equilibrium rows neither.
  result.friction_gradient = friction_parameter_rows(piece, law_, state).transpose() * result.psi_z;

  if (!(result.summary.reciprocal_condition > options_.singular_reciprocal_condition)) {
    result.summary.status = Status::kNumericalFailure;
    result.summary.message = "the piece's Jacobian is singular (is the friction coefficient too large for V4.4.1?)";
  } else {
    result.summary.status = Status::kConverged;
    result.summary.message = fmt::format("adjoint solved ({} of {} contact rows active, M {})", red.active_rows.size(), m,
                                         delassus.kind());
  }
  result.summary.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

AdjointSensitivity::StateDerivative AdjointSensitivity::state_derivative(
    const Piece& piece, const contact::DelassusMatrix& delassus, const Eigen::Ref<const Eigen::MatrixXd>& X,
    const Eigen::Ref<const Eigen::VectorXd>& u, const contact::ContactState& state,
    const Eigen::Ref<const Eigen::VectorXd>& h) const {
  const fem::DofMap& dofs = fem_.dofs();
  const linalg::SpdSolver& cholesky = fem_.factorization();
  const int dim = boundary_.dim();
  const PieceLinearization lin = linearize_piece(piece, law_, state);
  const Reduction red = reduce(lin);
  const Eigen::VectorXd Vh = fem_.mesh().design_jacobian() * h;
  const Eigen::MatrixXd dX = Eigen::Map<const Eigen::MatrixXd>(Vh.data(), dim, fem_.mesh().num_nodes()).transpose();
  const Eigen::VectorXd ra_full = fem_.residual_derivative(X, u, dX);
  const Eigen::VectorXd ra = dofs.restrict_forces(ra_full);
  Eigen::VectorXd rg = Eigen::VectorXd::Zero(boundary_.num_unknowns());
  const Eigen::VectorXd Bh = gap_matrix_ * h;
  for (Eigen::Index r : lin.gap_rows) rg(r) = Bh(r / dim);
  const Eigen::VectorXd Ainv_ra = cholesky.solve(ra);
  // (S M + C_z) δz = −r_g + S G A⁻¹ r_α; identity rows give δz = 0 on their index (their
  // right-hand side is zero), the rest is the A × R block.
  const Eigen::VectorXd rhs = -rg + lin.S * boundary_.times(Ainv_ra);
  const Eigen::SparseMatrix<double> S_at = sparse_block(lin.S, red.active_rows, red.touched_z);
  Eigen::MatrixXd K = Eigen::MatrixXd(sparse_block(lin.Cz, red.active_rows, red.free_z));
  Eigen::MatrixXd SM;  // the M part of K (its scale sets the floating border's)
  if (!red.touched_z.empty()) {
    SM = S_at * delassus.block(red.touched_z, red.free_z);
    K += SM;
  }
  Eigen::VectorXd r(static_cast<Eigen::Index>(red.active_rows.size()));
  for (std::size_t i = 0; i < red.active_rows.size(); ++i) r(static_cast<Eigen::Index>(i)) = rhs(red.active_rows[i]);
  const FloatingModes floating = floating_modes(fem_, boundary_, "state derivative");
  const Eigen::Index nr = floating.size();
  double border_sigma = 1.0;
  if (nr > 0) {
    // Bordered (class comment): [(S M + C_z)_{A,R}  (S W)_A; W_Rᵀ  0] (δz_R, δβ) = (r_A, Rᵀ r_α h).
    // The border scaled by σ as in subgradient(): δβ = σ × the solved border unknowns.
    const Eigen::Index na = K.rows();
    border_sigma = border_scale(SM);
    Eigen::MatrixXd Kb = Eigen::MatrixXd::Zero(na + nr, na + nr);
    Kb.topLeftCorner(na, na) = K;
    const Eigen::MatrixXd SW = lin.S * floating.W;
    for (std::size_t a = 0; a < red.active_rows.size(); ++a)
      Kb.block(static_cast<Eigen::Index>(a), na, 1, nr) = border_sigma * SW.row(red.active_rows[a]);
    for (std::size_t i = 0; i < red.free_z.size(); ++i)
      Kb.block(na, static_cast<Eigen::Index>(i), nr, 1) = border_sigma * floating.W.row(red.free_z[i]).transpose();
    Eigen::VectorXd rb(na + nr);
    rb.head(na) = r;
    rb.tail(nr) = border_sigma * (floating.R->transpose() * ra_full);
    K = std::move(Kb);
    r = std::move(rb);
  }
  StateDerivative out;
  out.contact = Eigen::VectorXd::Zero(boundary_.num_unknowns());
  Eigen::VectorXd beta;
  if (K.size()) {
    Eigen::VectorXd dz;
    if (!linalg::blas::lu_solve(K, r, dz, out.reciprocal_condition)) out.reciprocal_condition = 0.0;
    for (std::size_t i = 0; i < red.free_z.size(); ++i) out.contact(red.free_z[i]) = dz(static_cast<Eigen::Index>(i));
    if (nr > 0) beta = border_sigma * dz.tail(nr);
  }
  out.status = out.reciprocal_condition > options_.singular_reciprocal_condition ? Status::kConverged : Status::kNumericalFailure;
  Eigen::VectorXd w = -ra;
  boundary_.add_transpose_times(out.contact, w);
  const Eigen::VectorXd du = cholesky.solve(w);
  out.displacement = dofs.expand_homogeneous(du);
  if (beta.size()) out.displacement += *floating.R * beta;  // δu = A_F⁺(Gᵀδz − r_α h) + R δβ
  return out;
}

}  // namespace frictopt::sensitivity
