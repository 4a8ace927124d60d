#include "solvers/solution_history.h"

#include <Eigen/Eigenvalues>

#include "core/check.h"

namespace kerf {
namespace {

using Row = Eigen::Matrix<double, 1, SolutionHistory::max_capacity>;

/// out = A V, row by row in parallel, each row's sums in registers (Eigen's
/// product of a sparse matrix and a row-major block sums into a run of
/// dynamic length: 7% of an implicit step's CPU against 3%).
template <class Block>
void sparse_times(const SparseMatrix& A, const Block& V, Block& out) {
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < A.rows(); ++i) {
    Row sum = Row::Zero();
    for (SparseMatrix::InnerIterator it(A, i); it; ++it) sum.noalias() += it.value() * V.row(it.index());
    out.row(i) = sum;
  }
}

}  // namespace

SolutionHistory::SolutionHistory(int capacity) : capacity_(capacity) {
  KERF_CHECK(capacity >= 0 && capacity <= max_capacity, "internal: a solution history of ", capacity,
             " solutions; at most ", max_capacity);
}

void SolutionHistory::remember(const Vector& x) {
  if (capacity_ <= 0) return;
  if (solutions_.rows() != x.size()) {
    solutions_.setZero(x.size(), max_capacity);
    count_ = next_ = 0;
  }
  solutions_.col(next_) = x;
  next_ = (next_ + 1) % capacity_;
  count_ = std::min(count_ + 1, capacity_);
}

void SolutionHistory::start(const SparseMatrix& A, const Vector& b, Vector& x0, Vector& r0) const {
  x0 = Vector::Zero(b.size());
  r0 = b;
  if (count_ == 0 || solutions_.rows() != b.size()) return;
  const auto V = solutions_.leftCols(count_);
  products_.resize(b.size(), max_capacity);  // allocates only when the length changes
  sparse_times(A, solutions_, products_);  // one pass over A
  const auto AV = products_.leftCols(count_);
  const Eigen::MatrixXd G = V.transpose() * AV;
  // Scaled to a unit diagonal, so that the cut-off below is relative to each
  // column's own size; columns with v^T A v <= 0 are left out.
  Vector scale = Vector::Zero(count_);
  for (int i = 0; i < count_; ++i)
    if (G(i, i) > 0.0) scale(i) = 1.0 / std::sqrt(G(i, i));
  if (scale.isZero()) return;
  const Eigen::MatrixXd scaled = scale.asDiagonal() * G * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scaled);
  if (eigen.info() != Eigen::Success) return;
  // The pseudo-inverse. A direction z of the scaled span with eigenvalue l has
  // A-norm sqrt(l), so round-off eps in its weight moves x0 by eps / sqrt(l)
  // relative: nearly repeated solutions (consecutive steps') still help down to
  // l ~ 1e-15 (4.05 -> 2.53 CG iterations a step at 1e-15, 2.81 at 1e-10), and
  // only directions the others repeat to round-off are left out.
  const Vector& values = eigen.eigenvalues();
  const double cutoff = 1e-15 * values.cwiseAbs().maxCoeff();
  const Vector projected = eigen.eigenvectors().transpose() * (scale.asDiagonal() * (V.transpose() * b));
  Vector weights = Vector::Zero(count_);
  for (int i = 0; i < count_; ++i)
    if (values(i) > cutoff) weights(i) = projected(i) / values(i);
  const Vector y = scale.asDiagonal() * (eigen.eigenvectors() * weights);
  if (!y.allFinite()) return;
  x0.noalias() = V * y;
  r0.noalias() = b - AV * y;
}

}  // namespace kerf
