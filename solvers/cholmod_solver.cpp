#include "solvers/cholmod_solver.h"

#include <cholmod.h>

#include <algorithm>
#include <limits>
#include <sstream>

#include "core/thread_scope.h"
#include "solvers/single_precision_factor.h"

namespace kerf {
namespace {

class CholmodSolver final : public LinearSolver {
 public:
  CholmodSolver() {
    cholmod_start(&common_);
    common_.supernodal = CHOLMOD_SUPERNODAL;
    common_.postorder = 1;  // (the default) subtrees as contiguous supernodes: SinglePrecisionFactor splits them
    common_.print = 0;
    common_.error_handler = nullptr;
  }
  ~CholmodSolver() override {
    if (factor_) cholmod_free_factor(&factor_, &common_);
    if (x_) cholmod_free_dense(&x_, &common_);
    if (y_) cholmod_free_dense(&y_, &common_);
    if (e_) cholmod_free_dense(&e_, &common_);
    cholmod_finish(&common_);
  }
  std::string name() const override { return "cholmod"; }
  bool exact_factor() const override { return true; }
  std::size_t factor_entries() const override {
    if (!factor_) return 0;
    return factor_->is_super ? factor_->xsize : factor_->nzmax;
  }

  LinearSolverStatus analyze(const SparseMatrix& pattern) override {
    SingleThreadScope single;
    cholmod_sparse view = wrap(pattern);
    if (factor_) cholmod_free_factor(&factor_, &common_);
    factor_ = cholmod_analyze(&view, &common_);
    if (!factor_ || common_.status < CHOLMOD_OK) return failure("symbolic analysis");
    return LinearSolverStatus::success();
  }

  LinearSolverStatus factorize(const SparseMatrix& A) override {
    if (!factor_) return LinearSolverStatus::failure("cholmod: factorize() before analyze()");
    // Threaded BLAS (Debian's OpenMP OpenBLAS, capped at the cores by
    // OMP_THREAD_LIMIT) on the supernodes: 214 -> 160 ms at 18 873 dofs (tet4),
    // 2.0 -> 1.8 s at 62 343 (tet10); the symbolic analysis and the triangular
    // solves stay on one thread.
    cholmod_sparse view = wrap(A);
    cholmod_factorize(&view, factor_, &common_);
    if (common_.status == CHOLMOD_NOT_POSDEF) {
      // The failed pivot, in the matrix's own numbering (the factor's is permuted).
      const Index column = static_cast<Index>(factor_->minor);
      const auto* permutation = static_cast<const int*>(factor_->Perm);
      const Index row = permutation && column < A.rows() ? permutation[column] : column;
      std::ostringstream why;
      why << "cholmod: the matrix is not positive definite (pivot " << column << " of " << A.rows()
          << " failed, at row " << row << ")";
      LinearSolverStatus status = LinearSolverStatus::failure(why.str());
      status.failed_row = row;
      return status;
    }
    if (common_.status < CHOLMOD_OK) return failure("numeric factorization");
    LinearSolverStatus status = numerically_singular(A);
    single_.clear();
    if (status.ok && keep_single_) single_.copy(*factor_);
    return status;
  }

  void keep_single_precision_copy() override { keep_single_ = true; }

  LinearSolverStatus precondition(const Vector& b, Vector& x) override {
    if (single_.empty()) return solve(b, x);
    single_.solve(b, x);
    return LinearSolverStatus::success();
  }

  LinearSolverStatus solve(const Vector& b, Vector& x) override {
    SingleThreadScope single;
    cholmod_dense rhs{};
    rhs.nrow = static_cast<size_t>(b.size());
    rhs.ncol = 1;
    rhs.nzmax = rhs.nrow;
    rhs.d = rhs.nrow;
    rhs.x = const_cast<double*>(b.data());
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;
    // solve2 reuses its workspaces, so repeated solves do not allocate.
    if (!cholmod_solve2(CHOLMOD_A, factor_, &rhs, nullptr, &x_, nullptr, &y_, &e_, &common_))
      return failure("solve");
    x = Eigen::Map<const Vector>(static_cast<const double*>(x_->x), b.size());
    return LinearSolverStatus::success();
  }

 private:
  /// A view of the CSR matrix as CHOLMOD's CSC of its transpose: the same
  /// symmetric matrix; stype = 1 reads only the upper triangle.
  static cholmod_sparse wrap(const SparseMatrix& A) {
    cholmod_sparse s{};
    s.nrow = static_cast<size_t>(A.rows());
    s.ncol = static_cast<size_t>(A.cols());
    s.nzmax = static_cast<size_t>(A.nonZeros());
    s.p = const_cast<Index*>(A.outerIndexPtr());
    s.i = const_cast<Index*>(A.innerIndexPtr());
    s.x = const_cast<double*>(A.valuePtr());
    s.stype = 1;
    s.itype = CHOLMOD_INT;
    s.xtype = CHOLMOD_REAL;
    s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1;
    s.packed = 1;
    return s;
  }
  /// A factor whose smallest pivot is below 1e-20 of its largest: the matrix
  /// is positive definite only by round-off (a piece of the body held by
  /// nothing but a cut's smooth front), and a solve would answer displacements
  /// of 1e27 m. Refused like a failed pivot, naming the row.
  LinearSolverStatus numerically_singular(const SparseMatrix& A) const {
    if (!factor_->is_super) return LinearSolverStatus::success();
    const auto* super = static_cast<const int*>(factor_->super);
    const auto* pi = static_cast<const int*>(factor_->pi);
    const auto* px = static_cast<const int*>(factor_->px);
    const auto* x = static_cast<const double*>(factor_->x);
    double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
    Index column = -1;
    for (std::size_t s = 0; s < factor_->nsuper; ++s) {
      const int rows = pi[s + 1] - pi[s];
      for (int j = 0; j < super[s + 1] - super[s]; ++j) {
        const double pivot = x[px[s] + j + static_cast<std::size_t>(j) * rows];  // L's diagonal: sqrt(D)
        largest = std::max(largest, pivot * pivot);
        if (pivot * pivot < smallest) smallest = pivot * pivot, column = super[s] + j;
      }
    }
    if (column < 0 || smallest >= 1e-20 * largest) return LinearSolverStatus::success();
    const auto* permutation = static_cast<const int*>(factor_->Perm);
    const Index row = permutation && column < A.rows() ? permutation[column] : column;
    std::ostringstream why;
    why << "cholmod: the matrix is numerically singular (pivot " << column << " of " << A.rows() << ", at row "
        << row << ", is " << smallest / largest << " of the largest)";
    LinearSolverStatus status = LinearSolverStatus::failure(why.str());
    status.failed_row = row;
    return status;
  }
  LinearSolverStatus failure(const char* what) const {
    std::ostringstream why;
    why << "cholmod: " << what << " failed (status " << common_.status << ")";
    return LinearSolverStatus::failure(why.str());
  }

  cholmod_common common_{};
  cholmod_factor* factor_ = nullptr;
  bool keep_single_ = false;
  SinglePrecisionFactor single_;  // of factor_, when keep_single_
  cholmod_dense* x_ = nullptr;
  cholmod_dense* y_ = nullptr;
  cholmod_dense* e_ = nullptr;
};

}  // namespace

std::unique_ptr<LinearSolver> make_cholmod_solver() { return std::make_unique<CholmodSolver>(); }

}  // namespace kerf
