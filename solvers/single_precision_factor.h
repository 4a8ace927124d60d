#pragma once
// A single-precision copy of a supernodal Cholesky factor (CHOLMOD's) and its
// triangular solves. Each solve streams the factor twice and is bound by memory
// bandwidth, so half the bytes take about half the time; the answer is good to
// about kappa(A) times float's round-off, which is enough to precondition
// conjugate gradients on a matrix the factor no longer matches exactly anyway.
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "core/types.h"

struct cholmod_factor_struct;

namespace kerf {

class SinglePrecisionFactor {
 public:
  /// Copies L of A = P^T L L^T P; false (and empty) unless L is supernodal LL^T with int indices.
  bool copy(const cholmod_factor_struct& L);
  void clear();
  bool empty() const { return super_.empty(); }

  /// x = (P^T L L^T P)^-1 b, in single precision, on up to two threads (the
  /// same answer on one): the elimination tree's subtrees below its top chain
  /// are split into two parts of about equal bytes.
  void solve(const Vector& b, Vector& x) const;

 private:
  using Range = std::pair<Index, Index>;  // supernodes [first, second)
  void split_in_two();
  /// Supernode s's dense column-major block (its leading dimension is its height).
  const float* block(Index s, Index& first, Index& width, Index& height) const;
  /// Supernode s of L y = P b; rows of the top chain go to `top_share` (unless null).
  void forward(Index s, float* below, float* top_share) const;
  void backward(Index s, float* below) const;

  std::vector<int> permutation_;  // P: row k of the factor is row permutation_[k] of A
  std::vector<int> super_;        // supernode s holds columns super_[s] .. super_[s + 1]
  std::vector<int> row_start_;    // its rows: rows_[row_start_[s] .. row_start_[s + 1]]
  std::vector<int> rows_;
  std::vector<std::size_t> value_start_;  // its dense column-major block in values_
  std::vector<float> values_;
  std::array<std::vector<Range>, 2> parts_;  // whole subtrees, each part on a thread of its own
  Index top_first_supernode_ = 0;  // the top chain: supernodes from here to the last
  Index top_first_column_ = 0;
  mutable std::vector<float> y_;  // workspaces
  mutable std::array<std::vector<float>, 2> below_, top_share_;  // a part's
};

}  // namespace kerf
