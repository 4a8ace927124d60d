#include "solvers/eigen_solvers.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <sstream>

namespace kerf {
namespace {

using ColumnMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, Index>;

class EigenCgSolver final : public LinearSolver {
 public:
  explicit EigenCgSolver(double tolerance) { cg_.setTolerance(tolerance); }
  std::string name() const override { return "cg"; }
  LinearSolverStatus analyze(const SparseMatrix&) override { return LinearSolverStatus::success(); }
  LinearSolverStatus factorize(const SparseMatrix& A) override {
    matrix_ = A;
    cg_.setMaxIterations(std::max<Index>(1000, 10 * static_cast<Index>(A.rows())));
    cg_.compute(matrix_);
    return LinearSolverStatus::success();
  }
  LinearSolverStatus solve(const Vector& b, Vector& x) override {
    x = cg_.solve(b);
    iterations_ = static_cast<int>(cg_.iterations());
    if (cg_.info() != Eigen::Success || !x.allFinite()) {
      std::ostringstream why;
      why << "cg: no convergence after " << cg_.iterations() << " iterations (relative residual "
          << cg_.error() << "): the matrix may be singular or indefinite";
      return LinearSolverStatus::failure(why.str());
    }
    return LinearSolverStatus::success();
  }
  int last_iterations() const override { return iterations_; }

 private:
  SparseMatrix matrix_;
  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper> cg_;
  int iterations_ = 0;
};

class EigenLdltSolver final : public LinearSolver {
 public:
  std::string name() const override { return "ldlt"; }
  bool exact_factor() const override { return true; }
  LinearSolverStatus analyze(const SparseMatrix& pattern) override {
    ldlt_.analyzePattern(ColumnMatrix(pattern));
    return LinearSolverStatus::success();
  }
  LinearSolverStatus factorize(const SparseMatrix& A) override {
    ldlt_.factorize(ColumnMatrix(A));
    if (ldlt_.info() != Eigen::Success || (ldlt_.vectorD().array() <= 0.0).any())
      return LinearSolverStatus::failure(
          "ldlt: the matrix is singular or not positive definite (not enough constraints to remove rigid motion?)");
    return LinearSolverStatus::success();
  }
  LinearSolverStatus solve(const Vector& b, Vector& x) override {
    x = ldlt_.solve(b);
    if (ldlt_.info() != Eigen::Success) return LinearSolverStatus::failure("ldlt: solve failed");
    return LinearSolverStatus::success();
  }

 private:
  Eigen::SimplicialLDLT<ColumnMatrix, Eigen::Lower> ldlt_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_eigen_cg_solver(double tolerance) {
  return std::make_unique<EigenCgSolver>(tolerance);
}
std::unique_ptr<LinearSolver> make_eigen_ldlt_solver() { return std::make_unique<EigenLdltSolver>(); }

}  // namespace kerf
