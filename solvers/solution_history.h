#pragma once
// The last solutions of a sequence of similar symmetric positive definite
// systems (the steps of an implicit run), and the start they give the next
// solve: the Galerkin projection of Fischer (1998, "Projection techniques for
// iterative solution of Ax = b with successive right-hand sides").
#include <Eigen/Dense>

#include "solvers/sparse_assembly.h"

namespace kerf {

class SolutionHistory {
 public:
  /// Keeps at most `capacity` solutions (0 to max_capacity), the oldest dropped first.
  explicit SolutionHistory(int capacity);
  /// A V is one pass over A with a row's sums in registers, for this many columns.
  static constexpr int max_capacity = 8;

  /// Adds x; solutions of another length (the dofs changed) are forgotten.
  void remember(const Vector& x);
  int size() const { return count_; }

  /// x0 in the span V of the kept solutions with V^T A V y = V^T b, x0 = V y:
  /// the point of the span closest to A^-1 b in the A-norm (so never farther
  /// than x = 0), and its residual r0 = b - A x0. A is read once, for all
  /// kept solutions together. Solutions along which A is not positive, and
  /// those (nearly) dependent on the others, add nothing. With none kept: x0 = 0, r0 = b.
  void start(const SparseMatrix& A, const Vector& b, Vector& x0, Vector& r0) const;

 private:
  int capacity_;
  int count_ = 0;  // columns of solutions_ in use
  int next_ = 0;   // the column the next solution overwrites once all are in use
  // One solution a column, in no particular order (a span is all that counts);
  // row-major with max_capacity columns (those not in use zero), so that A V
  // reads each row of V as one contiguous run of fixed length.
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, max_capacity, Eigen::RowMajor>;
  RowMajor solutions_;
  mutable RowMajor products_;  // A V, a workspace kept between solves
};

}  // namespace kerf
