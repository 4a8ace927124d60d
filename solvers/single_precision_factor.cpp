#include "solvers/single_precision_factor.h"

#include <cholmod.h>
#include <omp.h>

#include <algorithm>
#include <numeric>

#include "core/parallel_failure.h"
#include "core/threads_worth_waking.h"
#include "solvers/float_kernels.h"

namespace kerf {
namespace {

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
  split_in_two();
  y_.resize(n);
  for (auto& below : below_) below.resize(L.maxesize);
  for (auto& share : top_share_) share.resize(n - top_first_column_);
  return true;
}

void SinglePrecisionFactor::split_in_two() {
  // The supernodal elimination tree; CHOLMOD's supernodes are postordered, so
  // each subtree is a contiguous run of supernodes ending at its root.
  const Index supernodes = static_cast<Index>(super_.size()) - 1;
  std::vector<Index> supernode_of_column(super_.back()), parent(supernodes, -1), first(supernodes);
  std::vector<std::vector<Index>> children(supernodes);
  std::vector<std::size_t> work(supernodes), count(supernodes, 1);
  std::iota(first.begin(), first.end(), 0);
  for (Index s = 0; s < supernodes; ++s)
    for (Index c = super_[s]; c < super_[s + 1]; ++c) supernode_of_column[c] = s;
  std::vector<Index> roots;
  for (Index s = 0; s < supernodes; ++s) {
    work[s] += value_start_[s + 1] - value_start_[s];
    const Index width = super_[s + 1] - super_[s];
    if (row_start_[s + 1] - row_start_[s] > width) {
      parent[s] = supernode_of_column[rows_[row_start_[s] + width]];
      children[parent[s]].push_back(s);
      work[parent[s]] += work[s];
      count[parent[s]] += count[s];
      first[parent[s]] = std::min(first[parent[s]], first[s]);
    } else {
      roots.push_back(s);
    }
  }
  for (auto& part : parts_) part.clear();
  bool postordered = true;
  for (Index s = 0; s < supernodes; ++s)
    postordered = postordered && parent[s] != s && (parent[s] < 0 || parent[s] > s) && count[s] == s - first[s] + 1u;
  if (!postordered) {  // CHOLMOD postorders by default; should it not, one part holds all, in order
    parts_[0].push_back({0, supernodes});
    top_first_supernode_ = supernodes;
    top_first_column_ = super_.back();
    return;
  }
  // Down from a single root while it has a single child: that chain (the top
  // separator, the last supernodes) runs alone; the subtrees below it share no
  // column and write to each other's rows never, to the chain's only.
  std::vector<Index> subtrees = roots;
  top_first_supernode_ = supernodes;
  if (roots.size() == 1) {
    Index s = roots[0];
    while (children[s].size() == 1) s = children[s][0];
    top_first_supernode_ = s;
    subtrees = children[s];
  }
  top_first_column_ = super_[top_first_supernode_];
  // The subtrees, largest first, each to the part with less work so far.
  std::sort(subtrees.begin(), subtrees.end(), [&](Index a, Index b) { return work[a] > work[b]; });
  std::array<std::size_t, 2> load{};
  for (Index root : subtrees) {
    const int lighter = load[0] <= load[1] ? 0 : 1;
    parts_[lighter].push_back({first[root], root + 1});
    load[lighter] += work[root];
  }
}

void SinglePrecisionFactor::clear() {
  for (auto* v : {&permutation_, &super_, &row_start_, &rows_}) v->clear();
  value_start_.clear();
  values_.clear();
  for (auto& part : parts_) part.clear();
}

const float* SinglePrecisionFactor::block(Index s, Index& first, Index& width, Index& height) const {
  first = super_[s];
  width = super_[s + 1] - first;
  height = row_start_[s + 1] - row_start_[s];
  return values_.data() + value_start_[s];
}

void SinglePrecisionFactor::forward(Index s, float* below, float* top_share) const {
  Index first, width, height;
  const float* L = block(s, first, width, height);
  float* top = y_.data() + first;
  const FloatKernels& kernels = float_kernels();  // the widest build the processor runs
  kernels.lower_solve(L, height, width, top);
  kernels.times(L + width, height, height - width, width, top, below);
  const int* row = rows_.data() + row_start_[s] + width;
  for (Index i = 0; i < height - width; ++i) {
    if (row[i] < top_first_column_ || !top_share)
      y_[row[i]] -= below[i];
    else
      top_share[row[i] - top_first_column_] += below[i];
  }
}

void SinglePrecisionFactor::backward(Index s, float* below) const {
  Index first, width, height;
  const float* L = block(s, first, width, height);
  const int* row = rows_.data() + row_start_[s] + width;
  for (Index i = 0; i < height - width; ++i) below[i] = y_[row[i]];
  float* top = y_.data() + first;
  const FloatKernels& kernels = float_kernels();
  kernels.subtract_transpose_times(L + width, height, height - width, width, below, top);
  kernels.lower_transpose_solve(L, height, width, top);
}

void SinglePrecisionFactor::solve(const Vector& b, Vector& x) const {
  const Index n = static_cast<Index>(permutation_.size());
  const Index supernodes = static_cast<Index>(super_.size()) - 1;
  for (Index k = 0; k < n; ++k) y_[k] = static_cast<float>(b[permutation_[k]]);
  // L y = P b: the two parts side by side, each adding what it takes from the
  // top chain's rows into its own share; then the shares, then the chain. The
  // same sums in the same order on one thread or two: the same answer.
  ParallelFailure failure;  // Eigen's products (float_kernels.h) may allocate a temporary: nothing may leave a region
  const bool parallel = worth_threads(static_cast<Index>(values_.size() / 384));  // an item: 384 entries
#pragma omp parallel for num_threads(std::min(2, omp_get_max_threads())) schedule(static, 1) if (parallel)
  for (int p = 0; p < 2; ++p)
    failure.run([&] {
      std::fill(top_share_[p].begin(), top_share_[p].end(), 0.0f);
      for (const auto& [begin, end] : parts_[p])
        for (Index s = begin; s < end; ++s) forward(s, below_[p].data(), top_share_[p].data());
    });
  failure.rethrow_if_failed();
  for (Index i = 0; i < n - top_first_column_; ++i) y_[top_first_column_ + i] -= top_share_[0][i] + top_share_[1][i];
  for (Index s = top_first_supernode_; s < supernodes; ++s) forward(s, below_[0].data(), nullptr);
  // L^T z = y: the chain first, then the parts, which read its rows only.
  for (Index s = supernodes - 1; s >= top_first_supernode_; --s) backward(s, below_[0].data());
#pragma omp parallel for num_threads(std::min(2, omp_get_max_threads())) schedule(static, 1) if (parallel)
  for (int p = 0; p < 2; ++p)
    failure.run([&] {
      for (const auto& [begin, end] : parts_[p])
        for (Index s = end - 1; s >= begin; --s) backward(s, below_[p].data());
    });
  failure.rethrow_if_failed();
  x.resize(n);
  for (Index k = 0; k < n; ++k) x[permutation_[k]] = y_[k];
}

}  // namespace kerf
