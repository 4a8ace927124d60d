#include "solvers/p_multigrid_solver.h"

#include <cmath>
#include <optional>
#include <sstream>

#include "solvers/cholmod_solver.h"
#include "solvers/compact_matrix.h"
#include "solvers/galerkin_product.h"
#include "solvers/largest_eigenvalue.h"

namespace kerf {
namespace {

class PMultigridSolver final : public LinearSolver {
 public:
  explicit PMultigridSolver(double tolerance) : tolerance_(tolerance) {}
  std::string name() const override { return "p_multigrid"; }
  bool needs_prolongation() const override { return true; }
  void set_prolongation(const SparseMatrix& P) override {
    prolongation_ = P;
    // Each coarse dof's own fine row (the corner's, weight 1): where a failed coarse pivot is.
    fine_row_of_coarse_.assign(static_cast<std::size_t>(P.cols()), -1);
    for (Index row = 0; row < P.rows(); ++row)
      for (SparseMatrix::InnerIterator it(P, row); it; ++it)
        if (it.value() == 1.0) fine_row_of_coarse_[it.index()] = row;
  }
  void set_row_share(const RowShare& share) override { block_ = share.block_size; }
  int last_iterations() const override { return iterations_; }

  LinearSolverStatus analyze(const SparseMatrix& pattern) override {
    if (prolongation_.rows() != pattern.rows() || prolongation_.cols() == 0)
      return LinearSolverStatus::failure("p_multigrid: no coarse space for the " + std::to_string(pattern.rows()) +
                                         " rows (the body has no quadratic cells)");
    galerkin_.emplace(prolongation_, pattern);
    compact_.analyze(pattern, block_);
    coarse_solver_ = make_cholmod_solver();
    return prefixed(coarse_solver_->analyze(galerkin_->coarse()));
  }

  LinearSolverStatus factorize(const SparseMatrix& A) override {
    if (!galerkin_) return LinearSolverStatus::failure("p_multigrid: factorize() before analyze()");
    matrix_ = &A;
    compact_.assign(A);
    inverse_diagonal_ = A.diagonal();
    for (Index i = 0; i < inverse_diagonal_.size(); ++i) {
      if (!(inverse_diagonal_[i] > 0.0)) {
        LinearSolverStatus status = LinearSolverStatus::failure(
            "p_multigrid: the matrix is not positive definite (diagonal entry " + std::to_string(i) + " is " +
            std::to_string(inverse_diagonal_[i]) + ")");
        status.failed_row = i;
        return status;
      }
      inverse_diagonal_[i] = 1.0 / inverse_diagonal_[i];
    }
    // PETSc's Chebyshev targets for multigrid smoothing: [0.1, 1.1] of the estimate.
    const double largest = 1.1 * largest_jacobi_eigenvalue();
    if (!(largest > 0.0) || !std::isfinite(largest))
      return LinearSolverStatus::failure("p_multigrid: the smoother's eigenvalue estimate is " +
                                         std::to_string(largest) + ": the matrix is not positive definite");
    lower_ = 0.1 * largest, upper_ = largest;
    return prefixed(coarse_solver_->factorize(galerkin_->compute(A)));
  }

  LinearSolverStatus solve(const Vector& b, Vector& x) override;

 private:
  /// The largest eigenvalue of D^-1 A (D = diag A; A's compact copy) by 12
  /// steps of Lanczos (solvers/largest_eigenvalue.h, with D as the mass).
  double largest_jacobi_eigenvalue() const {
    const Vector diagonal = inverse_diagonal_.cwiseInverse();
    const FreeDofs every(static_cast<Index>(diagonal.size()), {});
    LanczosOptions options;
    options.max_iterations = 12;
    options.start_entry = [](Index i) { return std::sin(12.9898 * static_cast<double>(i) + 1.0); };
    const auto times = [this](const Vector& x, Vector& y) { compact_.multiply(x, y); };
    return largest_eigenvalue(times, diagonal, every, options).ritz_value;
  }
  void smooth(const Vector& b, Vector& x, bool from_zero);
  LinearSolverStatus precondition_v_cycle(const Vector& r, Vector& z);
  /// A coarse level's status in the matrix's terms: its failed row is the coarse dof's own fine row.
  LinearSolverStatus prefixed(LinearSolverStatus status) const {
    if (!status.ok) status.message = "p_multigrid, the coarse (linear) level: " + status.message;
    if (status.failed_row && *status.failed_row >= 0 &&
        *status.failed_row < static_cast<Index>(fine_row_of_coarse_.size()) &&
        fine_row_of_coarse_[*status.failed_row] >= 0)
      status.failed_row = fine_row_of_coarse_[*status.failed_row];
    else
      status.failed_row.reset();
    return status;
  }

  double tolerance_;
  SparseMatrix prolongation_;
  std::vector<Index> fine_row_of_coarse_;
  std::optional<GalerkinProduct> galerkin_;
  std::unique_ptr<LinearSolver> coarse_solver_;
  const SparseMatrix* matrix_ = nullptr;  // the last factorized A (linear_solver.h: kept until the next)
  CompactMatrix compact_;  // A in single precision and node blocks, for the smoother
  int block_ = 1;          // dofs a node, when the free dofs are whole nodes
  Vector inverse_diagonal_;
  double lower_ = 0.0, upper_ = 0.0;
  // Chebyshev steps a smoothing. The 2.5 mm tet10 cantilever (62 343 dofs):
  // 34, 21, 17 CG iterations for degree 1, 2, 3; the solve 0.34, 0.32, 0.40 s.
  static constexpr int degree_ = 2;
  int iterations_ = 0;
  Vector residual_, direction_, product_, coarse_rhs_, coarse_x_;
};

/// Chebyshev smoothing of A x = b on D^-1 A's interval [lower_, upper_],
/// degree_ steps; from x = 0 the first residual is b itself.
void PMultigridSolver::smooth(const Vector& b, Vector& x, bool from_zero) {
  const double theta = 0.5 * (upper_ + lower_), delta = 0.5 * (upper_ - lower_), sigma = theta / delta;
  if (from_zero) {
    residual_ = b;
  } else {
    compact_.multiply(x, product_);
    residual_ = b - product_;
  }
  direction_ = inverse_diagonal_.cwiseProduct(residual_) / theta;
  double rho = 1.0 / sigma;
  for (int k = 1;; ++k) {
    x += direction_;
    if (k == degree_) break;
    compact_.multiply(direction_, product_);
    residual_ -= product_;
    const double rho_next = 1.0 / (2.0 * sigma - rho);
    direction_ = rho_next * rho * direction_ + (2.0 * rho_next / delta) * inverse_diagonal_.cwiseProduct(residual_);
    rho = rho_next;
  }
}

/// z = B r, B the symmetric V-cycle: smooth, correct on the coarse level, smooth again.
LinearSolverStatus PMultigridSolver::precondition_v_cycle(const Vector& r, Vector& z) {
  z.setZero(r.size());
  smooth(r, z, true);
  compact_.multiply(z, product_);
  residual_ = r - product_;
  coarse_rhs_.noalias() = prolongation_.transpose() * residual_;
  LinearSolverStatus status = prefixed(coarse_solver_->solve(coarse_rhs_, coarse_x_));
  if (!status.ok) return status;
  z.noalias() += prolongation_ * coarse_x_;
  smooth(r, z, false);
  return status;
}

LinearSolverStatus PMultigridSolver::solve(const Vector& b, Vector& x) {
  const Index n = static_cast<Index>(b.size());
  x.setZero(n);
  iterations_ = 0;
  const double b_norm = b.norm();
  if (b_norm == 0.0) return LinearSolverStatus::success();
  Vector r = b, z, p, q;
  LinearSolverStatus status = precondition_v_cycle(r, z);
  if (!status.ok) return status;
  p = z;
  double rz = r.dot(z), r_norm = b_norm;
  const int most = 1000;
  while (iterations_ < most) {
    q.noalias() = *matrix_ * p;
    const double pq = p.dot(q);
    ++iterations_;
    if (!(pq > 0.0) || !std::isfinite(rz)) {
      std::ostringstream why;
      why << "p_multigrid: conjugate gradients met p^T A p = " << pq << " at iteration " << iterations_
          << ": the matrix (or the preconditioner) is not positive definite";
      return LinearSolverStatus::failure(why.str());
    }
    const double alpha = rz / pq;
    x += alpha * p;
    r -= alpha * q;
    r_norm = r.norm();
    if (r_norm <= tolerance_ * b_norm) return LinearSolverStatus::success();
    status = precondition_v_cycle(r, z);
    if (!status.ok) return status;
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  std::ostringstream why;
  why << "p_multigrid: no convergence after " << most << " iterations (relative residual " << r_norm / b_norm
      << ", asked " << tolerance_ << ")";
  return LinearSolverStatus::failure(why.str());
}

}  // namespace

std::unique_ptr<LinearSolver> make_p_multigrid_solver(double relative_tolerance) {
  return std::make_unique<PMultigridSolver>(relative_tolerance);
}

}  // namespace kerf
