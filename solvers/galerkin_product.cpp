#include "solvers/galerkin_product.h"

#include <algorithm>

#include "core/check.h"

namespace kerf {
namespace {

/// Calls visit(J, w) for each coarse column J that coarse row I reaches
/// through A, with the weight w = sum P_iI A_ij P_jJ (pattern only: A = 1).
template <class Visit>
void for_each_reach(const SparseMatrix& Pt, const SparseMatrix& P, const Index* outer, const Index* inner,
                    const double* values, Index I, const Visit& visit) {
  for (SparseMatrix::InnerIterator fine(Pt, I); fine; ++fine) {
    const Index i = fine.index();
    const double wi = fine.value();
    for (Index k = outer[i]; k < outer[i + 1]; ++k) {
      const Index j = inner[k];
      const double a = values ? values[k] : 1.0;
      for (SparseMatrix::InnerIterator coarse(P, j); coarse; ++coarse) visit(coarse.index(), wi * a * coarse.value());
    }
  }
}

}  // namespace

GalerkinProduct::GalerkinProduct(const SparseMatrix& P, const SparseMatrix& A_pattern) : P_(P), Pt_(P.transpose()) {
  KERF_CHECK(A_pattern.rows() == P.rows() && A_pattern.cols() == P.rows(), "GalerkinProduct: A is " +
             std::to_string(A_pattern.rows()) + " x " + std::to_string(A_pattern.cols()) + ", P has " +
             std::to_string(P.rows()) + " rows");
  P_.makeCompressed();
  Pt_.makeCompressed();
  const Index n = static_cast<Index>(P.cols());
  std::vector<std::vector<Index>> columns(static_cast<std::size_t>(n));  // each coarse row's, found in parallel
#pragma omp parallel
  {
    std::vector<Index> seen(static_cast<std::size_t>(n), -1);
#pragma omp for schedule(dynamic, 64)
    for (Index I = 0; I < n; ++I) {
      std::vector<Index>& row = columns[I];
      for_each_reach(Pt_, P_, A_pattern.outerIndexPtr(), A_pattern.innerIndexPtr(), nullptr, I, [&](Index J, double) {
        if (seen[J] != I) seen[J] = I, row.push_back(J);
      });
      std::sort(row.begin(), row.end());
    }
  }
  coarse_.resize(n, n);
  Index count = 0;
  for (const std::vector<Index>& row : columns) count += static_cast<Index>(row.size());
  coarse_.resizeNonZeros(count);
  Index* outer = coarse_.outerIndexPtr();
  outer[0] = 0;
  for (Index I = 0; I < n; ++I) {
    std::copy(columns[I].begin(), columns[I].end(), coarse_.innerIndexPtr() + outer[I]);
    outer[I + 1] = outer[I] + static_cast<Index>(columns[I].size());
  }
  std::fill(coarse_.valuePtr(), coarse_.valuePtr() + count, 0.0);
}

const SparseMatrix& GalerkinProduct::compute(const SparseMatrix& A) {
  const Index n = static_cast<Index>(coarse_.rows());
  const Index* outer = coarse_.outerIndexPtr();
  const Index* inner = coarse_.innerIndexPtr();
  double* out = coarse_.valuePtr();
#pragma omp parallel
  {
    Vector row = Vector::Zero(n);  // this thread's dense row, zero between rows
#pragma omp for schedule(dynamic, 64)
    for (Index I = 0; I < n; ++I) {
      for_each_reach(Pt_, P_, A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr(), I,
                     [&](Index J, double w) { row[J] += w; });
      for (Index k = outer[I]; k < outer[I + 1]; ++k) out[k] = row[inner[k]], row[inner[k]] = 0.0;
    }
  }
  return coarse_;
}

}  // namespace kerf
