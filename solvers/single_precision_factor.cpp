#include "solvers/single_precision_factor.h"

#include <cholmod.h>

#include <Eigen/Core>
#include <algorithm>

namespace kerf {
namespace {

using FloatVector = Eigen::Map<Eigen::VectorXf>;
using FloatBlock = Eigen::Map<const Eigen::MatrixXf, 0, Eigen::OuterStride<>>;

template <class T>
std::vector<T> copied(const void* p, std::size_t n) {
  const auto* begin = static_cast<const int*>(p);
  return std::vector<T>(begin, begin + n);
}

}  // namespace

bool SinglePrecisionFactor::copy(const cholmod_factor& L) {
  clear();
  if (!L.is_super || !L.is_ll || L.itype != CHOLMOD_INT || L.xtype != CHOLMOD_REAL || L.dtype != CHOLMOD_DOUBLE)
    return false;
  const std::size_t n = L.n, supernodes = L.nsuper;
  permutation_ = copied<int>(L.Perm, n);
  super_ = copied<int>(L.super, supernodes + 1);
  row_start_ = copied<int>(L.pi, supernodes + 1);
  rows_ = copied<int>(L.s, static_cast<std::size_t>(row_start_.back()));
  value_start_ = copied<std::size_t>(L.px, supernodes + 1);
  const auto* x = static_cast<const double*>(L.x);
  values_.assign(x, x + value_start_.back());
  y_.resize(n);
  below_.resize(L.maxesize);
  return true;
}

void SinglePrecisionFactor::clear() {
  for (auto* v : {&permutation_, &super_, &row_start_, &rows_}) v->clear();
  value_start_.clear();
  values_.clear();
}

void SinglePrecisionFactor::solve(const Vector& b, Vector& x) const {
  const Index n = static_cast<Index>(permutation_.size());
  for (Index k = 0; k < n; ++k) y_[k] = static_cast<float>(b[permutation_[k]]);
  const Index supernodes = static_cast<Index>(super_.size()) - 1;
  // Supernode s: a dense block of `height` rows by `width` columns, its top
  // square the diagonal block (lower triangular), the rest the rows below.
  auto block = [&](Index s, Index& first, Index& width, Index& height) {
    first = super_[s];
    width = super_[s + 1] - first;
    height = row_start_[s + 1] - row_start_[s];
    return FloatBlock(values_.data() + value_start_[s], height, width, Eigen::OuterStride<>(height));
  };
  for (Index s = 0; s < supernodes; ++s) {  // L y = P b
    Index first, width, height;
    const FloatBlock L = block(s, first, width, height);
    FloatVector top(y_.data() + first, width);
    L.topRows(width).triangularView<Eigen::Lower>().solveInPlace(top);
    FloatVector below(below_.data(), height - width);
    below.noalias() = L.bottomRows(height - width) * top;
    const int* row = rows_.data() + row_start_[s] + width;
    for (Index i = 0; i < height - width; ++i) y_[row[i]] -= below[i];
  }
  for (Index s = supernodes - 1; s >= 0; --s) {  // L^T z = y
    Index first, width, height;
    const FloatBlock L = block(s, first, width, height);
    FloatVector below(below_.data(), height - width);
    const int* row = rows_.data() + row_start_[s] + width;
    for (Index i = 0; i < height - width; ++i) below[i] = y_[row[i]];
    FloatVector top(y_.data() + first, width);
    top.noalias() -= L.bottomRows(height - width).transpose() * below;
    L.topRows(width).triangularView<Eigen::Lower>().transpose().solveInPlace(top);
  }
  x.resize(n);
  for (Index k = 0; k < n; ++k) x[permutation_[k]] = y_[k];
}

}  // namespace kerf
