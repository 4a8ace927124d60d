#pragma once
// A symmetric matrix's copy for passes that need only an approximation of it
// (a multigrid smoother): values in single precision and, where the matrix is
// made of whole b x b node blocks, one column index a block. The 2.5 mm tet10
// cantilever's A streams 12 bytes a nonzero in CSR, 4.4 here.
#include <vector>

#include "solvers/sparse_assembly.h"

namespace kerf {

class CompactMatrix {
 public:
  /// Takes A's pattern: blocks of `block` (1, 2 or 3) rows and columns where
  /// every block row's rows hold the same whole blocks, else scalar entries.
  void analyze(const SparseMatrix& A, int block);
  /// Takes A's values (same pattern as analyzed).
  void assign(const SparseMatrix& A);
  /// y = A x, summed in double precision, rows shared among the threads.
  void multiply(const Vector& x, Vector& y) const;
  /// The block size taken: 1 when A's pattern is not made of whole blocks.
  int block() const { return block_; }

 private:
  template <int B>
  void multiply_blocks(const Vector& x, Vector& y) const;

  int block_ = 1;
  Index rows_ = 0;
  std::vector<Index> outer_;     // by block row, into inner_
  std::vector<Index> inner_;     // block column of each block
  std::vector<float> values_;    // each block's B x B values, row-major
  std::vector<Index> source_;    // each value's position in A's values
};

}  // namespace kerf
