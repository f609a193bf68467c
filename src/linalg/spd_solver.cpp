// SPDX-License-Identifier: MIT
#include "frictopt/linalg/spd_solver.hpp"

#include "cholmod_solver.hpp"
#include "frictopt/core/enum_table.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::linalg {
namespace {
constexpr auto kBackendNames = frictopt::detail::make_enum_table<SpdBackend>(std::pair{SpdBackend::kCholmod, "cholmod"});
}  // namespace

std::string_view to_string(SpdBackend backend) { return kBackendNames.name(backend); }

SpdBackend parse_spd_backend(std::string_view name) { return kBackendNames.parse(name, "linear_solver.backend"); }

std::unique_ptr<SpdSolver> SpdSolver::create(const Options& options) {
  switch (options.backend) {
    case SpdBackend::kCholmod: return std::make_unique<CholmodSolver>();
  }
  throw InvalidInput("SpdSolver::Options::backend = " + std::to_string(static_cast<int>(options.backend)) +
                     "; expected one of " + kBackendNames.spellings());
}

Status SpdSolver::analyze(const Eigen::SparseMatrix<double>&, const std::vector<int>&) {
  throw InvalidInput("SpdSolver '" + std::string(name()) +
                     "': analyze with a trailing block requested; this backend has no Schur factor "
                     "(supports_trailing_factor() is false)");
}

Eigen::VectorXd SpdSolver::solve(const Eigen::Ref<const Eigen::VectorXd>& b) const { return solve_many(b); }

Eigen::MatrixXd SpdSolver::trailing_factor() const {
  throw InvalidInput("SpdSolver '" + std::string(name()) +
                     "': trailing_factor() requested; this backend has no Schur factor");
}

}  // namespace frictopt::linalg
