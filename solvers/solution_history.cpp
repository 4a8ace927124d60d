#include "solvers/solution_history.h"

#include <Eigen/Eigenvalues>

namespace kerf {
namespace {

/// out = A V for V of `Cols` columns (row-major, row length `stride`), row by
/// row in parallel: the row's sums stay in registers (Eigen's product of a
/// sparse matrix and a row-major block sums into a run of dynamic length).
template <int Cols>
void times_columns(const SparseMatrix& A, const double* V, Index stride, double* out) {
  const Index* outer = A.outerIndexPtr();
  const Index* inner = A.innerIndexPtr();
  const double* values = A.valuePtr();
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < A.rows(); ++i) {
    Eigen::Matrix<double, 1, Cols> sum = Eigen::Matrix<double, 1, Cols>::Zero();
    for (Index p = outer[i]; p < outer[i + 1]; ++p)
      sum.noalias() += values[p] * Eigen::Map<const Eigen::Matrix<double, 1, Cols>>(V + inner[p] * stride);
    Eigen::Map<Eigen::Matrix<double, 1, Cols>>(out + i * stride) = sum;
  }
}

}  // namespace

void SolutionHistory::remember(const Vector& x) {
  if (capacity_ <= 0) return;
  if (solutions_.rows() != x.size()) {
    solutions_.setZero(x.size(), capacity_);
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
  products_.resize(b.size(), capacity_);  // allocates only when the length changes
  auto AV = products_.leftCols(count_);
  if (capacity_ == 8 && A.isCompressed())  // the implicit steps' history: all 8 columns (unused ones are zero)
    times_columns<8>(A, solutions_.data(), capacity_, products_.data());
  else
    AV.noalias() = A * V;  // one pass over A
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
