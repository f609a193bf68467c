// SPDX-License-Identifier: MIT
#include "frictopt/petsc/contact_newton_solver.hpp"

#include <fmt/format.h>
#include <petscksp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "distributed_stiffness.hpp"
#include "krylov_delassus.hpp"
#include "krylov_spd_solver.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/petsc/petsc_session.hpp"
#include "petsc_check.hpp"
#include "projection_jacobian.hpp"
#include "transposed_adjoint.hpp"

namespace frictopt::petsc {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The option names of a PETSc options string ("-ksp_type cg -pc_type gamg" -> -ksp_type,
// -pc_type): tokens that start with '-' followed by a letter (so "-1e-3" is a value).
std::vector<std::string> option_names(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> names;
  for (std::string token; in >> token;)
    if (token.size() > 1 && token[0] == '-' && std::isalpha(static_cast<unsigned char>(token[1]))) names.push_back(token);
  return names;
}

// One owned contact node: its index among the contact nodes, its first DOF (local offset).
struct LocalContactNode {
  int index = 0;
  int local_dof = 0;
  int global_dof = 0;
};

// The Alart–Curnier linearization at one node (see the header): χ = [λ̂ > 0] and the
// projection's generalized derivatives; z = (q, λ) = (proj, max(0, λ̂)).
struct NodeLinearization {
  bool in_contact = false;
  ProjectionLinearization projection;
  Eigen::Vector2d q = Eigen::Vector2d::Zero();
  double lambda = 0.0;
};

}  // namespace

void ContactNewtonSolver::Options::validate() const {
  const auto fail = [](const std::string& field, const std::string& value, const std::string& expected) {
    throw InvalidInput(fmt::format("ContactNewtonSolver::Options::{} = {}; expected {}", field, value, expected));
  };
  if (!(relative_tolerance > 0 && relative_tolerance < 1)) fail("relative_tolerance", fmt::format("{:g}", relative_tolerance), "in (0, 1)");
  if (max_iterations < 1) fail("max_iterations", std::to_string(max_iterations), ">= 1");
  if (max_halvings < 0) fail("max_halvings", std::to_string(max_halvings), ">= 0");
  if (!(krylov_relative_tolerance > 0 && krylov_relative_tolerance < 1))
    fail("krylov_relative_tolerance", fmt::format("{:g}", krylov_relative_tolerance), "in (0, 1)");
  if (krylov_max_iterations < 1) fail("krylov_max_iterations", std::to_string(krylov_max_iterations), ">= 1");
  if (!(augmentation > 0 && std::isfinite(augmentation))) fail("augmentation", fmt::format("{:g}", augmentation), "finite and > 0");
  if (!(classification_tolerance > 0 && classification_tolerance < 1))
    fail("classification_tolerance", fmt::format("{:g}", classification_tolerance), "in (0, 1)");
  if (!(adjoint_relative_tolerance > 0 && adjoint_relative_tolerance < 1))
    fail("adjoint_relative_tolerance", fmt::format("{:g}", adjoint_relative_tolerance), "in (0, 1)");
}

std::string ContactNewtonSolver::Summary::brief_report() const {
  return fmt::format(
      "petsc semismooth Newton: {} ({}); {} Newton / {} Krylov iterations ({}, {} ranks); relative residual "
      "{:.2e}, KKT residual {:.2e}, complementarity gap {:.2e}; assembly {:.3f} s, solve {:.3f} s",
      to_string(status), message, newton_iterations, krylov_iterations, krylov_type, num_ranks, relative_residual,
      kkt_residual, complementarity_gap, assembly_seconds, solve_seconds);
}

std::string ContactNewtonSolver::AdjointSummary::brief_report() const {
  return fmt::format("petsc adjoint (one transposed solve): {} ({}); {} Krylov iterations ({}), relative residual {:.2e}; "
                     "{:.3f} s",
                     to_string(status), message, krylov_iterations, krylov_type, relative_residual, seconds);
}

struct ContactNewtonSolver::Impl {
  const fem::LinearElasticity& fem;
  const contact::ContactBoundary& boundary;
  contact::FrictionLaw law;
  const Options& options;
  int dim;
  detail::DistributedStiffness stiffness;
  Mat J = nullptr;
  KSP ksp = nullptr;
  Vec u = nullptr, F = nullptr, du = nullptr, u_try = nullptr, F_try = nullptr;
  std::vector<PetscInt> prescribed;        // owned prescribed DOFs (global indices)
  std::vector<double> prescribed_values;   // their values u_d
  std::vector<LocalContactNode> contact_nodes;
  std::vector<NodeLinearization> linearization;  // per owned contact node, at the last residual
  bool options_checked = false;
  bool jacobian_is_stiffness = false;  // J = K with Γ_u eliminated (no contact rows)
  KSP spd_ksp = nullptr;               // CG for solves with that J (the Delassus columns)
  PetscOptions database = nullptr;  // the solver's own options (Options::petsc_options)
  std::unique_ptr<detail::TransposedAdjoint> adjoint;  // created at the first subgradient()
  double rho = 0.0;

  Impl(const fem::LinearElasticity& f, const contact::ContactBoundary& b, contact::FrictionLaw l, const Options& o)
      : fem(f), boundary(b), law(std::move(l)), options(o), dim(f.mesh().dim()), stiffness(f) {
    const fem::DofMap& dofs = fem.dofs();
    for (int dof = stiffness.first_dof(); dof < stiffness.end_dof(); ++dof)
      if (!dofs.is_free(dof)) {
        prescribed.push_back(dof);
        prescribed_values.push_back(dofs.prescribed_values()(dof));
      }
    for (Eigen::Index i = 0; i < boundary.num_nodes(); ++i) {
      const int node = boundary.nodes()[static_cast<std::size_t>(i)];
      if (stiffness.owns_node(node))
        contact_nodes.push_back({static_cast<int>(i), node * dim - stiffness.first_dof(), node * dim});
    }
    for (Vec* v : {&u, &F, &du, &u_try, &F_try}) *v = stiffness.create_vector();
    FRICTOPT_PETSC_CALL(KSPCreate(PETSC_COMM_WORLD, &ksp));
    // Defaults (docs/petsc-engine.md): GMRES, because the Jacobian is non-symmetric where nodes
    // slip, preconditioned by smoothed-aggregation AMG with the rigid-body near-null space.
    FRICTOPT_PETSC_CALL(KSPSetType(ksp, KSPGMRES));
    FRICTOPT_PETSC_CALL(KSPGMRESSetRestart(ksp, 100));
    PC pc;
    FRICTOPT_PETSC_CALL(KSPGetPC(ksp, &pc));
    FRICTOPT_PETSC_CALL(PCSetType(pc, PCGAMG));
    FRICTOPT_PETSC_CALL(KSPSetTolerances(ksp, options.krylov_relative_tolerance, 0.0, PETSC_DEFAULT,
                                         options.krylov_max_iterations));
    // A private options database: two solvers (or two cases) in one process do not see each
    // other's options, and "unused" means unused by this solver.
    FRICTOPT_PETSC_CALL(PetscOptionsCreate(&database));
    FRICTOPT_PETSC_CALL(PetscOptionsInsertString(database, options.petsc_options.c_str()));
    FRICTOPT_PETSC_CALL(PetscObjectSetOptions(reinterpret_cast<PetscObject>(ksp), database));
    FRICTOPT_PETSC_CALL(PetscObjectSetOptions(reinterpret_cast<PetscObject>(pc), database));
    FRICTOPT_PETSC_CALL(KSPSetFromOptions(ksp));
  }

  ~Impl() {
    adjoint.reset();  // its KSP reads `database`
    KSPDestroy(&ksp);
    KSPDestroy(&spd_ksp);
    PetscOptionsDestroy(&database);
    for (Vec* v : {&u, &F, &du, &u_try, &F_try}) VecDestroy(v);
    MatDestroy(&J);
  }

  // F(u) (see the header); with `contact` false every contact node is free (F = r there): the
  // free elastic response's equations. Stores the node linearizations.
  void residual(Vec x, Vec out, const Eigen::VectorXd& gaps, bool contact) {
    FRICTOPT_PETSC_CALL(MatMult(stiffness.matrix(), x, out));
    FRICTOPT_PETSC_CALL(VecAXPY(out, -1.0, stiffness.load()));
    PetscScalar* r = nullptr;
    const PetscScalar* ux = nullptr;
    FRICTOPT_PETSC_CALL(VecGetArray(out, &r));
    FRICTOPT_PETSC_CALL(VecGetArrayRead(x, &ux));
    const int first = stiffness.first_dof();
    for (PetscInt dof : prescribed) r[dof - first] = 0.0;
    linearization.assign(contact_nodes.size(), NodeLinearization{});
    const int t = dim - 1;  // tangential components
    for (std::size_t k = 0; k < contact_nodes.size() && contact; ++k) {
      const LocalContactNode& node = contact_nodes[k];
      double* rn = r + node.local_dof;
      const double* un = ux + node.local_dof;
      Eigen::Vector2d q_trial = Eigen::Vector2d::Zero();
      for (int c = 0; c < t; ++c) q_trial(c) = -rn[c] + rho * un[c];  // q̂ = q + ρ u_t, q = −r_t
      const double w = un[t] + gaps(node.index);
      const double lambda_trial = rn[t] - rho * w;  // λ̂ = λ − ρ w, λ = r_ν
      NodeLinearization& lin = linearization[k];
      lin.in_contact = lambda_trial > 0.0;
      lin.lambda = std::max(0.0, lambda_trial);
      lin.projection = linearize_projection(law, q_trial, lin.lambda);
      lin.q = lin.projection.value;
      rn[t] -= lin.lambda;
      for (int c = 0; c < t; ++c) rn[c] += lin.q(c);
    }
    FRICTOPT_PETSC_CALL(VecRestoreArrayRead(x, &ux));
    FRICTOPT_PETSC_CALL(VecRestoreArray(out, &r));
  }

  // The generalized Jacobian at the last residual: K with the contact rows replaced and the
  // prescribed rows and columns zeroed (diagonal ρ). Rows of node i, with K_ν, K_t its rows of K
  // and E the unit rows:
  //   row_ν = (1 − χ) K_ν + χ ρ E_ν,
  //   row_t = (I − J_P) K_t + ρ J_P E_t + χ ∂_sP (K_ν − ρ E_ν).
  void jacobian(bool contact) {
    jacobian_is_stiffness = !contact;
    if (J == nullptr) {  // K's pattern exists after its first assembly
      FRICTOPT_PETSC_CALL(MatDuplicate(stiffness.matrix(), MAT_COPY_VALUES, &J));
      FRICTOPT_PETSC_CALL(MatSetNearNullSpace(J, stiffness.near_null_space()));
      FRICTOPT_PETSC_CALL(PetscObjectSetOptions(reinterpret_cast<PetscObject>(J), database));
      FRICTOPT_PETSC_CALL(MatSetFromOptions(J));
      FRICTOPT_PETSC_CALL(KSPSetOperators(ksp, J, J));
    } else {
      FRICTOPT_PETSC_CALL(MatCopy(stiffness.matrix(), J, SAME_NONZERO_PATTERN));
    }
    const int t = dim - 1;
    std::vector<PetscInt> cols;
    std::vector<std::vector<double>> rows(static_cast<std::size_t>(dim));
    std::vector<double> out;
    for (std::size_t k = 0; k < contact_nodes.size() && contact; ++k) {
      const LocalContactNode& node = contact_nodes[k];
      const NodeLinearization& lin = linearization[k];
      for (int c = 0; c < dim; ++c) {
        PetscInt n = 0;
        const PetscInt* cc = nullptr;
        const PetscScalar* vv = nullptr;
        FRICTOPT_PETSC_CALL(MatGetRow(stiffness.matrix(), node.global_dof + c, &n, &cc, &vv));
        if (c == 0) cols.assign(cc, cc + n);
        FRICTOPT_ASSERT(static_cast<std::size_t>(n) == cols.size(), "rows of a node block share their pattern");
        rows[static_cast<std::size_t>(c)].assign(vv, vv + n);
        FRICTOPT_PETSC_CALL(MatRestoreRow(stiffness.matrix(), node.global_dof + c, &n, &cc, &vv));
      }
      const std::size_t n = cols.size();
      const auto diagonal_slot = [&](int c) {
        return static_cast<std::size_t>(std::lower_bound(cols.begin(), cols.end(), node.global_dof + c) - cols.begin());
      };
      const double chi = lin.in_contact ? 1.0 : 0.0;
      const std::vector<double>& Kn = rows[static_cast<std::size_t>(t)];
      // Normal row.
      out.assign(n, 0.0);
      for (std::size_t j = 0; j < n; ++j) out[j] = (1.0 - chi) * Kn[j];
      out[diagonal_slot(t)] += chi * rho;
      PetscInt row = node.global_dof + t;
      FRICTOPT_PETSC_CALL(MatSetValues(J, 1, &row, static_cast<PetscInt>(n), cols.data(), out.data(), INSERT_VALUES));
      // Tangential rows.
      const Eigen::Matrix2d& JP = lin.projection.d_x;
      for (int a = 0; a < t; ++a) {
        out.assign(n, 0.0);
        for (int b = 0; b < t; ++b) {
          const double coefficient = (a == b ? 1.0 : 0.0) - JP(a, b);
          if (coefficient != 0.0)
            for (std::size_t j = 0; j < n; ++j) out[j] += coefficient * rows[static_cast<std::size_t>(b)][j];
          out[diagonal_slot(b)] += rho * JP(a, b);
        }
        const double ds = chi * lin.projection.d_s(a);
        if (ds != 0.0) {
          for (std::size_t j = 0; j < n; ++j) out[j] += ds * Kn[j];
          out[diagonal_slot(t)] -= ds * rho;
        }
        row = node.global_dof + a;
        FRICTOPT_PETSC_CALL(MatSetValues(J, 1, &row, static_cast<PetscInt>(n), cols.data(), out.data(), INSERT_VALUES));
      }
    }
    FRICTOPT_PETSC_CALL(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    FRICTOPT_PETSC_CALL(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
    // Γ_u: the increments vanish there, so rows and columns go (keeps K's symmetry for AMG).
    FRICTOPT_PETSC_CALL(MatZeroRowsColumns(J, static_cast<PetscInt>(prescribed.size()), prescribed.data(), rho,
                                           nullptr, nullptr));
  }

  // du = −J⁻¹F. Returns KSP's reason; adds the iterations.
  KSPConvergedReason linear_solve(int& krylov_iterations) {
    FRICTOPT_PETSC_CALL(VecScale(F, -1.0));
    FRICTOPT_PETSC_CALL(VecSet(du, 0.0));
    FRICTOPT_PETSC_CALL(KSPSolve(ksp, F, du));
    FRICTOPT_PETSC_CALL(VecScale(F, -1.0));
    PetscInt its = 0;
    FRICTOPT_PETSC_CALL(KSPGetIterationNumber(ksp, &its));
    krylov_iterations += static_cast<int>(its);
    KSPConvergedReason reason;
    FRICTOPT_PETSC_CALL(KSPGetConvergedReason(ksp, &reason));
    if (!options_checked) {
      options_checked = true;
      for (const std::string& name : option_names(options.petsc_options)) {
        PetscBool used = PETSC_FALSE;  // the database stores names without the leading dash
        FRICTOPT_PETSC_CALL(PetscOptionsUsed(database, name.c_str() + 1, &used));
        if (!used)
          throw InvalidInput(fmt::format(
              "solver.petsc_options: \"{}\" was not used by any PETSc object; expected an option of the active "
              "KSP/PC/Mat (misspelled, or for a solver that is not selected? see docs/petsc-engine.md)",
              name));
      }
    }
    return reason;
  }

  // A⁻¹ rhs on the free DOFs (A = K restricted to them): CG + GAMG on J = K with Γ_u
  // eliminated, to a relative residual of 1e-12 (the sensitivity reads these as exact).
  Eigen::VectorXd free_solve(const Eigen::VectorXd& rhs_free) {
    if (!jacobian_is_stiffness) jacobian(false);
    if (spd_ksp == nullptr) {
      FRICTOPT_PETSC_CALL(KSPCreate(PETSC_COMM_WORLD, &spd_ksp));
      FRICTOPT_PETSC_CALL(KSPSetType(spd_ksp, KSPCG));
      PC pc;
      FRICTOPT_PETSC_CALL(KSPGetPC(spd_ksp, &pc));
      FRICTOPT_PETSC_CALL(PCSetType(pc, PCGAMG));
      FRICTOPT_PETSC_CALL(KSPSetTolerances(spd_ksp, 1e-12, 0.0, PETSC_DEFAULT, options.krylov_max_iterations));
    }
    FRICTOPT_PETSC_CALL(KSPSetOperators(spd_ksp, J, J));
    const fem::DofMap& dofs = fem.dofs();
    PetscScalar* b = nullptr;
    FRICTOPT_PETSC_CALL(VecGetArray(F_try, &b));
    for (int dof = stiffness.first_dof(); dof < stiffness.end_dof(); ++dof) {
      const int k = dofs.free_index(dof);
      b[dof - stiffness.first_dof()] = k >= 0 ? rhs_free(k) : 0.0;
    }
    FRICTOPT_PETSC_CALL(VecRestoreArray(F_try, &b));
    FRICTOPT_PETSC_CALL(VecSet(du, 0.0));
    FRICTOPT_PETSC_CALL(KSPSolve(spd_ksp, F_try, du));
    KSPConvergedReason reason;
    FRICTOPT_PETSC_CALL(KSPGetConvergedReason(spd_ksp, &reason));
    if (reason < 0)
      throw NumericalFailure(fmt::format("PETSc engine: a solve with the stiffness (Delassus column) did not converge: {}",
                                         KSPConvergedReasons[reason]));
    return dofs.restrict(gather(du));
  }

  // The full vector on every rank.
  Eigen::VectorXd gather(Vec v) const {
    VecScatter scatter;
    Vec all;
    FRICTOPT_PETSC_CALL(VecScatterCreateToAll(v, &scatter, &all));
    FRICTOPT_PETSC_CALL(VecScatterBegin(scatter, v, all, INSERT_VALUES, SCATTER_FORWARD));
    FRICTOPT_PETSC_CALL(VecScatterEnd(scatter, v, all, INSERT_VALUES, SCATTER_FORWARD));
    PetscInt n = 0;
    FRICTOPT_PETSC_CALL(VecGetSize(all, &n));
    const PetscScalar* a = nullptr;
    FRICTOPT_PETSC_CALL(VecGetArrayRead(all, &a));
    Eigen::VectorXd out = Eigen::Map<const Eigen::VectorXd>(a, n);
    FRICTOPT_PETSC_CALL(VecRestoreArrayRead(all, &a));
    FRICTOPT_PETSC_CALL(VecScatterDestroy(&scatter));
    FRICTOPT_PETSC_CALL(VecDestroy(&all));
    return out;
  }

  double norm(Vec v) const {
    PetscReal value = 0.0;
    FRICTOPT_PETSC_CALL(VecNorm(v, NORM_2, &value));
    return value;
  }
};

ContactNewtonSolver::ContactNewtonSolver(const fem::LinearElasticity& fem, const contact::ContactBoundary& boundary,
                                         contact::FrictionLaw law, Options options)
    : options_(std::move(options)) {
  options_.validate();
  if (law.dim() != fem.mesh().dim())
    throw InvalidInput(fmt::format("ContactNewtonSolver: a {}D friction law for a {}D body", law.dim(), fem.mesh().dim()));
  PetscSession::require();
  impl_ = std::make_unique<Impl>(fem, boundary, std::move(law), options_);
}

ContactNewtonSolver::~ContactNewtonSolver() = default;

ContactNewtonSolver::Summary ContactNewtonSolver::solve(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                        const Eigen::Ref<const Eigen::VectorXd>& gaps,
                                                        Eigen::VectorXd& displacement, contact::ContactState& state) {
  Impl& m = *impl_;
  const int dim = m.dim;
  const int t = dim - 1;
  FRICTOPT_ASSERT(gaps.size() == m.boundary.num_nodes(), "one gap per contact node");
  Summary summary;
  summary.num_ranks = PetscSession::size();
  auto start = std::chrono::steady_clock::now();
  m.stiffness.assemble(X);
  summary.assembly_seconds = seconds_since(start);
  start = std::chrono::steady_clock::now();
  {
    KSPType ksp_type;
    PC pc;
    PCType pc_type;
    FRICTOPT_PETSC_CALL(KSPGetType(m.ksp, &ksp_type));
    FRICTOPT_PETSC_CALL(KSPGetPC(m.ksp, &pc));
    FRICTOPT_PETSC_CALL(PCGetType(pc, &pc_type));
    summary.krylov_type = fmt::format("{}+{}", ksp_type ? ksp_type : "?", pc_type ? pc_type : "?");
  }

  // ρ = augmentation · mean diag(K) over the contact normal DOFs.
  {
    Vec diagonal = m.stiffness.create_vector();
    FRICTOPT_PETSC_CALL(MatGetDiagonal(m.stiffness.matrix(), diagonal));
    const PetscScalar* d = nullptr;
    FRICTOPT_PETSC_CALL(VecGetArrayRead(diagonal, &d));
    double local[2] = {0.0, 0.0}, global[2] = {0.0, 0.0};
    for (const LocalContactNode& node : m.contact_nodes) {
      local[0] += d[node.local_dof + t];
      local[1] += 1.0;
    }
    FRICTOPT_PETSC_CALL(VecRestoreArrayRead(diagonal, &d));
    FRICTOPT_PETSC_CALL(VecDestroy(&diagonal));
    MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    double mean = global[1] > 0 ? global[0] / global[1] : 0.0;
    if (!(mean > 0)) {  // no contact node: any positive scale of the stiffness
      PetscReal max_diag = 1.0;
      FRICTOPT_PETSC_CALL(MatNorm(m.stiffness.matrix(), NORM_INFINITY, &max_diag));
      mean = max_diag > 0 ? max_diag : 1.0;
    }
    m.rho = m.options.augmentation * mean;
  }

  // u_d on Γ_u, zero elsewhere: the unloaded state, whose ‖F‖ is the force scale.
  FRICTOPT_PETSC_CALL(VecSet(m.u, 0.0));
  FRICTOPT_PETSC_CALL(VecSetValues(m.u, static_cast<PetscInt>(m.prescribed.size()), m.prescribed.data(),
                                   m.prescribed_values.data(), INSERT_VALUES));
  FRICTOPT_PETSC_CALL(VecAssemblyBegin(m.u));
  FRICTOPT_PETSC_CALL(VecAssemblyEnd(m.u));
  m.residual(m.u, m.F, gaps, false);
  double scale = m.norm(m.F);
  if (!(scale > 0)) scale = 1.0;

  // The free elastic response (no contact forces): one linear solve; c = G u_free + (0, g) gives
  // the displacement scale of the classification, as in the direct engine, and it is the cold start.
  m.jacobian(false);
  KSPConvergedReason reason = m.linear_solve(summary.krylov_iterations);
  summary.last_krylov_reason = KSPConvergedReasons[reason];
  const auto krylov_failure = [&](const char* what) {
    summary.status = Status::kNumericalFailure;
    summary.message = fmt::format("the Krylov solve of the {} did not converge: {} after {} iterations ({})", what,
                                  KSPConvergedReasons[reason], summary.krylov_iterations, summary.krylov_type);
  };
  double c_scale = 0.0;
  if (reason < 0) {
    krylov_failure("free elastic response");
  } else {
    FRICTOPT_PETSC_CALL(VecAXPY(m.u, 1.0, m.du));
    const PetscScalar* ux = nullptr;
    FRICTOPT_PETSC_CALL(VecGetArrayRead(m.u, &ux));
    for (const LocalContactNode& node : m.contact_nodes) {
      for (int c = 0; c < t; ++c) c_scale = std::max(c_scale, std::abs(ux[node.local_dof + c]));
      c_scale = std::max(c_scale, std::abs(ux[node.local_dof + t] + gaps(node.index)));
    }
    FRICTOPT_PETSC_CALL(VecRestoreArrayRead(m.u, &ux));
    MPI_Allreduce(MPI_IN_PLACE, &c_scale, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
    if (displacement.size() == m.fem.mesh().num_dofs()) {  // warm start (prescribed values kept)
      PetscScalar* ux_w = nullptr;
      FRICTOPT_PETSC_CALL(VecGetArray(m.u, &ux_w));
      for (int dof = m.stiffness.first_dof(); dof < m.stiffness.end_dof(); ++dof)
        if (m.fem.dofs().is_free(dof)) ux_w[dof - m.stiffness.first_dof()] = displacement(dof);
      FRICTOPT_PETSC_CALL(VecRestoreArray(m.u, &ux_w));
    }
  }

  // Semismooth Newton with backtracking on ‖F‖₂.
  double residual_norm = kNaN;
  if (summary.status == Status::kNotRun) {
    m.residual(m.u, m.F, gaps, true);
    residual_norm = m.norm(m.F);
    for (int k = 0;; ++k) {
      if (residual_norm <= m.options.relative_tolerance * scale) {
        summary.status = Status::kConverged;
        summary.message = fmt::format("‖F‖ <= {:.1e}·‖F(u_d)‖", m.options.relative_tolerance);
        break;
      }
      if (!std::isfinite(residual_norm)) {
        summary.status = Status::kDiverged;
        summary.message = "the residual is not finite";
        break;
      }
      if (k == m.options.max_iterations) {
        summary.status = Status::kMaxIterations;
        summary.message = fmt::format("{} Newton iterations; ‖F‖/‖F(u_d)‖ = {:.2e} > {:.1e}", k,
                                      residual_norm / scale, m.options.relative_tolerance);
        break;
      }
      m.jacobian(true);
      reason = m.linear_solve(summary.krylov_iterations);
      summary.last_krylov_reason = KSPConvergedReasons[reason];
      ++summary.newton_iterations;
      if (reason < 0) {
        krylov_failure(fmt::format("Newton step {}", k + 1).c_str());
        break;
      }
      // Backtracking (Armijo on ‖F‖₂ with c = 1e-4); the linearizations of the accepted point
      // are the ones the next Jacobian uses, so the trial residual is evaluated last.
      double step = 1.0, trial_norm = kNaN;
      for (int h = 0;; ++h) {
        FRICTOPT_PETSC_CALL(VecWAXPY(m.u_try, step, m.du, m.u));
        m.residual(m.u_try, m.F_try, gaps, true);
        trial_norm = m.norm(m.F_try);
        if (trial_norm <= (1.0 - 1e-4 * step) * residual_norm) break;
        if (h == m.options.max_halvings) {  // take the full step: semismooth Newton's local phase
          ++summary.nonmonotone_steps;
          if (step != 1.0) {
            step = 1.0;
            FRICTOPT_PETSC_CALL(VecWAXPY(m.u_try, step, m.du, m.u));
            m.residual(m.u_try, m.F_try, gaps, true);
            trial_norm = m.norm(m.F_try);
          }
          break;
        }
        step *= 0.5;
      }
      const double u_norm = m.norm(m.u_try);
      summary.last_relative_increment = step * m.norm(m.du) / (u_norm > 0.0 ? u_norm : 1.0);
      std::swap(m.u, m.u_try);
      std::swap(m.F, m.F_try);
      residual_norm = trial_norm;
    }
  }
  summary.relative_residual = residual_norm / scale;

  // u on every rank, and z = (q, λ) of the owned contact nodes summed over the ranks.
  displacement = m.gather(m.u);
  const Eigen::Index p = m.boundary.num_nodes();
  state = contact::ContactState(dim, p);
  if (m.linearization.size() == m.contact_nodes.size())
    for (std::size_t k = 0; k < m.contact_nodes.size(); ++k) {
      const int i = m.contact_nodes[k].index;
      for (int c = 0; c < t; ++c) state.z(dim * i + c) = m.linearization[k].q(c);
      state.z(dim * i + t) = m.linearization[k].lambda;
    }
  MPI_Allreduce(MPI_IN_PLACE, state.z.data(), static_cast<int>(state.z.size()), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  state.gradient.resize(dim * p);
  for (Eigen::Index i = 0; i < p; ++i) {
    const int node = m.boundary.nodes()[static_cast<std::size_t>(i)];
    for (int c = 0; c < t; ++c) state.gradient(dim * i + c) = -displacement(node * dim + c);
    state.gradient(dim * i + t) = displacement(node * dim + t) + gaps(i);
  }
  state.slip_bound = state.normal_forces();
  const std::vector<contact::FrictionLaw> laws{m.law};
  const contact::ContactResiduals residuals =
      contact::contact_residuals(laws, state.slip_bound, state.z, state.gradient, dim, c_scale);
  summary.kkt_residual = residuals.kkt_residual;
  summary.complementarity_gap = residuals.complementarity_gap;
  contact::classify_nodes(state, laws, m.options.classification_tolerance, c_scale);
  summary.solve_seconds = seconds_since(start);
  return summary;
}

std::shared_ptr<const contact::DelassusMatrix> ContactNewtonSolver::delassus() {
  Impl* impl = impl_.get();
  return std::make_shared<detail::KrylovDelassus>([impl](const Eigen::VectorXd& rhs) { return impl->free_solve(rhs); },
                                                  impl->boundary);
}

std::vector<ContactNewtonSolver::NodePiece> ContactNewtonSolver::newton_piece() const {
  const Impl& m = *impl_;
  // Per node (in_contact, face, index), encoded as integers and summed over the owning ranks.
  std::vector<int> code(static_cast<std::size_t>(3 * m.boundary.num_nodes()), 0);
  if (m.linearization.size() == m.contact_nodes.size())
    for (std::size_t k = 0; k < m.contact_nodes.size(); ++k) {
      const auto i = static_cast<std::size_t>(m.contact_nodes[k].index);
      code[3 * i] = m.linearization[k].in_contact ? 1 : 0;
      code[3 * i + 1] = static_cast<int>(m.linearization[k].projection.face.face);
      code[3 * i + 2] = m.linearization[k].projection.face.index + 1;  // −1 -> 0 so that sums work
    }
  MPI_Allreduce(MPI_IN_PLACE, code.data(), static_cast<int>(code.size()), MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
  std::vector<NodePiece> out(static_cast<std::size_t>(m.boundary.num_nodes()));
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i].in_contact = code[3 * i] != 0;
    out[i].face = {static_cast<contact::FrictionFace>(code[3 * i + 1]), code[3 * i + 2] - 1};
  }
  return out;
}

ContactNewtonSolver::SubgradientResult ContactNewtonSolver::subgradient(
    const Eigen::Ref<const Eigen::MatrixXd>& X, const Eigen::Ref<const Eigen::VectorXd>& u,
    const Eigen::Ref<const Eigen::VectorXd>& d_alpha, const Eigen::Ref<const Eigen::VectorXd>& d_displacement,
    const Eigen::Ref<const Eigen::VectorXd>& d_contact, const Eigen::Ref<const Eigen::MatrixXd>& gap_matrix) {
  Impl& m = *impl_;
  const auto start = std::chrono::steady_clock::now();
  const int dim = m.dim;
  const int t = dim - 1;
  const Eigen::Index p = m.boundary.num_nodes();
  const Eigen::Index num_dofs = m.fem.mesh().num_dofs();
  if (u.size() != num_dofs || d_displacement.size() != num_dofs || (d_contact.size() != 0 && d_contact.size() != dim * p) ||
      gap_matrix.rows() != p || (d_alpha.size() != 0 && d_alpha.size() != gap_matrix.cols()))
    throw InvalidInput(fmt::format(
        "ContactNewtonSolver::subgradient: sizes u {}, ∇_u J {}, ∇_z J {}, B̃ {} × {}, ∇_α J {}; expected {} DOFs, {} "
        "contact unknowns (or none), {} gap rows and as many design columns as ∇_α J",
        u.size(), d_displacement.size(), d_contact.size(), gap_matrix.rows(), gap_matrix.cols(), d_alpha.size(),
        num_dofs, dim * p, p));
  FRICTOPT_ASSERT(m.linearization.size() == m.contact_nodes.size(), "subgradient() after a solve()");
  const int first = m.stiffness.first_dof(), end = m.stiffness.end_dof();
  const fem::DofMap& dofs = m.fem.dofs();
  const auto gz = [&](Eigen::Index k) { return d_contact.size() ? d_contact(k) : 0.0; };

  // w = Pᵀ∇_z J: z = (q, λ) = (−r_t, r_ν) at a contact node, so the z-part of the cost enters
  // through r = K u − f.
  Vec w = m.stiffness.create_vector(), b = m.stiffness.create_vector(), psi = m.stiffness.create_vector();
  FRICTOPT_PETSC_CALL(VecSet(w, 0.0));
  {
    PetscScalar* wa = nullptr;
    FRICTOPT_PETSC_CALL(VecGetArray(w, &wa));
    for (const LocalContactNode& node : m.contact_nodes) {
      for (int c = 0; c < t; ++c) wa[node.local_dof + c] = -gz(dim * node.index + c);
      wa[node.local_dof + t] = gz(dim * node.index + t);
    }
    FRICTOPT_PETSC_CALL(VecRestoreArray(w, &wa));
  }
  // b = −(∇_u J + K w) on the free DOFs, 0 on Γ_u (J_N's rows and columns there are ρ·I).
  FRICTOPT_PETSC_CALL(MatMult(m.stiffness.matrix(), w, b));
  {
    PetscScalar* ba = nullptr;
    FRICTOPT_PETSC_CALL(VecGetArray(b, &ba));
    for (int dof = first; dof < end; ++dof)
      ba[dof - first] = dofs.is_free(dof) ? -(ba[dof - first] + d_displacement(dof)) : 0.0;
    FRICTOPT_PETSC_CALL(VecRestoreArray(b, &ba));
  }

  // J_N at the converged state: the linearizations stored by the last residual (the accepted
  // point's), so the piece is newton_piece().
  m.jacobian(true);
  if (!m.adjoint)
    m.adjoint = std::make_unique<detail::TransposedAdjoint>(m.stiffness.near_null_space(), m.database,
                                                            m.options.adjoint_relative_tolerance,
                                                            m.options.krylov_max_iterations);
  const detail::TransposedAdjoint::Solve solved = m.adjoint->solve(m.J, b, psi);
  SubgradientResult result;
  result.summary.krylov_iterations = solved.iterations;
  result.summary.relative_residual = solved.relative_residual;
  result.summary.krylov_type = solved.krylov_type;
  result.summary.krylov_reason = KSPConvergedReasons[solved.reason];

  // v = L_rᵀψ + w and the gap coefficients c_i. Per contact node (rows ν, t of F; see jacobian()):
  //   ∂F_ν = (1 − χ) ∂r_ν + χρ ∂u_ν + χρ ∂g,
  //   ∂F_t = (I − J_P) ∂r_t + χ ∂_sP ∂r_ν + ρ J_P ∂u_t − χρ ∂_sP (∂u_ν + ∂g),
  // so (L_rᵀψ)_t = (I − J_P)ᵀψ_t, (L_rᵀψ)_ν = (1 − χ)ψ_ν + χ ∂_sPᵀψ_t, c = χρ(ψ_ν − ∂_sPᵀψ_t).
  // Elsewhere F = r on free DOFs (L_r = I) and v = ψ; ψ = 0 on Γ_u (exactly: its rows of b are 0).
  Eigen::VectorXd coefficients = Eigen::VectorXd::Zero(p);
  {
    PetscScalar* va = nullptr;
    const PetscScalar* wa = nullptr;
    FRICTOPT_PETSC_CALL(VecGetArray(psi, &va));
    FRICTOPT_PETSC_CALL(VecGetArrayRead(w, &wa));
    for (int dof = first; dof < end; ++dof) {
      const int l = dof - first;
      va[l] = dofs.is_free(dof) ? va[l] + wa[l] : 0.0;
    }
    for (std::size_t k = 0; k < m.contact_nodes.size(); ++k) {
      const LocalContactNode& node = m.contact_nodes[k];
      const NodeLinearization& lin = m.linearization[k];
      const double chi = lin.in_contact ? 1.0 : 0.0;
      const Eigen::Matrix2d& JP = lin.projection.d_x;
      double psi_t[2] = {0.0, 0.0};
      for (int a = 0; a < t; ++a) psi_t[a] = va[node.local_dof + a] - wa[node.local_dof + a];
      const double psi_n = va[node.local_dof + t] - wa[node.local_dof + t];
      double ds_psi = 0.0;
      for (int a = 0; a < t; ++a) ds_psi += chi * lin.projection.d_s(a) * psi_t[a];
      for (int c = 0; c < t; ++c) {
        double value = wa[node.local_dof + c];
        for (int a = 0; a < t; ++a) value += ((a == c ? 1.0 : 0.0) - JP(a, c)) * psi_t[a];
        va[node.local_dof + c] = value;
      }
      va[node.local_dof + t] = wa[node.local_dof + t] + (1.0 - chi) * psi_n + ds_psi;
      coefficients(node.index) = chi * m.rho * psi_n - m.rho * ds_psi;
    }
    FRICTOPT_PETSC_CALL(VecRestoreArrayRead(w, &wa));
    FRICTOPT_PETSC_CALL(VecRestoreArray(psi, &va));
  }
  MPI_Allreduce(MPI_IN_PLACE, coefficients.data(), static_cast<int>(p), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  const Eigen::VectorXd v = m.gather(psi);
  for (Vec* vec : {&w, &b, &psi}) FRICTOPT_PETSC_CALL(VecDestroy(vec));

  // ξ = ∇_α J + ∇_α[vᵀ(K(α)u − f(α))] + B̃ᵀc (fem's element-wise shape-derivative kernel).
  result.subgradient = m.fem.shape_derivative(X, u, v);
  if (d_alpha.size()) result.subgradient += d_alpha;
  result.subgradient += gap_matrix.transpose() * coefficients;
  if (solved.reason < 0) {
    result.summary.status = Status::kNumericalFailure;
    result.summary.message = fmt::format("the transposed Krylov solve did not converge: {} after {} iterations",
                                         result.summary.krylov_reason, solved.iterations);
  } else {
    result.summary.status = Status::kConverged;
    result.summary.message = fmt::format("Jᵀψ solved ({})", result.summary.krylov_reason);
  }
  result.summary.seconds = seconds_since(start);
  return result;
}

std::unique_ptr<linalg::SpdSolver> ContactNewtonSolver::stiffness_solver() {
  Impl* impl = impl_.get();
  return std::make_unique<detail::KrylovSpdSolver>([impl](const Eigen::VectorXd& rhs) { return impl->free_solve(rhs); });
}

}  // namespace frictopt::petsc
