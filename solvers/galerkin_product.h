#pragma once
// The coarse operator of a two-level method, A_c = P^T A P, for a fixed
// pattern of A: the pattern of A_c is found once, its values at each new A.
#include "solvers/sparse_assembly.h"

namespace kerf {

class GalerkinProduct {
 public:
  /// P: fine x coarse (a few entries a row); A: fine x fine, symmetric pattern.
  GalerkinProduct(const SparseMatrix& P, const SparseMatrix& A_pattern);
  /// P^T A P's pattern, values zero.
  const SparseMatrix& coarse() const { return coarse_; }
  /// Fills coarse() with P^T A P, A in the pattern given at construction.
  const SparseMatrix& compute(const SparseMatrix& A);

 private:
  SparseMatrix P_;
  SparseMatrix Pt_;  // P^T, row-major: each coarse row's fine rows
  SparseMatrix coarse_;
};

}  // namespace kerf
