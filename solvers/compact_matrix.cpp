#include "solvers/compact_matrix.h"

#include "core/check.h"

namespace kerf {
namespace {

/// Whether every block row of A is B rows with the same columns, in whole blocks.
bool made_of_blocks(const SparseMatrix& A, int B) {
  if (B == 1) return true;
  if (A.rows() % B != 0) return false;
  const Index* outer = A.outerIndexPtr();
  const Index* inner = A.innerIndexPtr();
  for (Index first = 0; first < A.rows(); first += B) {
    const Index begin = outer[first], count = outer[first + 1] - begin;
    if (count % B != 0) return false;
    for (Index k = 0; k < count; k += B)
      for (int j = 0; j < B; ++j)
        if (inner[begin + k + j] != inner[begin + k] + j || inner[begin + k] % B != 0) return false;
    for (int r = 1; r < B; ++r) {
      const Index other = outer[first + r];
      if (outer[first + r + 1] - other != count) return false;
      for (Index k = 0; k < count; ++k)
        if (inner[other + k] != inner[begin + k]) return false;
    }
  }
  return true;
}

}  // namespace

void CompactMatrix::analyze(const SparseMatrix& A, int block) {
  KERF_CHECK(block >= 1 && block <= 3, "CompactMatrix: block size " + std::to_string(block) + ", expected 1 to 3");
  block_ = made_of_blocks(A, block) ? block : 1;
  const int B = block_;
  rows_ = static_cast<Index>(A.rows());
  const Index* outer = A.outerIndexPtr();
  const Index* inner = A.innerIndexPtr();
  const Index block_rows = rows_ / B;
  outer_.assign(static_cast<std::size_t>(block_rows) + 1, 0);
  for (Index I = 0; I < block_rows; ++I) outer_[I + 1] = outer_[I] + (outer[B * I + 1] - outer[B * I]) / B;
  inner_.resize(static_cast<std::size_t>(outer_[block_rows]));
  source_.resize(inner_.size() * B * B);
#pragma omp parallel for schedule(static)
  for (Index I = 0; I < block_rows; ++I)
    for (Index k = 0; k < outer_[I + 1] - outer_[I]; ++k) {
      const Index block = outer_[I] + k;
      inner_[block] = inner[outer[B * I] + B * k] / B;
      Index* to = &source_[static_cast<std::size_t>(block) * B * B];
      for (int r = 0; r < B; ++r)
        for (int j = 0; j < B; ++j) to[r * B + j] = outer[B * I + r] + B * k + j;
    }
  values_.resize(source_.size());
}

void CompactMatrix::assign(const SparseMatrix& A) {
  const double* in = A.valuePtr();
  const Index* source = source_.data();
  float* out = values_.data();
  const std::ptrdiff_t count = static_cast<std::ptrdiff_t>(values_.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t k = 0; k < count; ++k) out[k] = static_cast<float>(in[source[k]]);
}

template <int B>
void CompactMatrix::multiply_blocks(const Vector& x, Vector& y) const {
  const Index block_rows = rows_ / B;
  const Index* outer = outer_.data();
  const Index* inner = inner_.data();
  const float* values = values_.data();
  const double* in = x.data();
  double* out = y.data();
#pragma omp parallel for schedule(static)
  for (Index I = 0; I < block_rows; ++I) {
    double sum[B] = {};
    for (Index k = outer[I]; k < outer[I + 1]; ++k) {
      const float* b = values + static_cast<std::size_t>(k) * B * B;
      const double* xj = in + static_cast<std::size_t>(inner[k]) * B;
      for (int r = 0; r < B; ++r)
        for (int j = 0; j < B; ++j) sum[r] += static_cast<double>(b[r * B + j]) * xj[j];
    }
    for (int r = 0; r < B; ++r) out[static_cast<std::size_t>(I) * B + r] = sum[r];
  }
}

void CompactMatrix::multiply(const Vector& x, Vector& y) const {
  y.resize(rows_);
  switch (block_) {
    case 3: return multiply_blocks<3>(x, y);
    case 2: return multiply_blocks<2>(x, y);
    default: return multiply_blocks<1>(x, y);
  }
}

}  // namespace kerf
