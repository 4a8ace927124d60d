#pragma once
// The floor under FEM tet4 stiffness assembly: the least work one pass must do,
// written bare: per cell, the linear-elastic K_e = V G D G^T (16 blocks of
// 3 x 3 from the four constant gradients) and f_e = K_e u_e, added into the
// CSR values through a slot table built once (no search, no sink), cells run
// in kerf's own conflict-free schedule.
#include <array>
#include <vector>

#include "geometry/cell_schedule.h"
#include "geometry/mesh.h"
#include "solvers/sparse_assembly.h"

namespace kerf::bench {

class Tet4AssemblyFloor {
 public:
  /// `K`: the pattern the cells write (dofs 3 per node, node-major).
  Tet4AssemblyFloor(const Mesh& mesh, const SparseMatrix& K, double lambda, double mu, int threads);
  /// K's values and f overwritten with K(u) and K u.
  void assemble(const double* u, SparseMatrix& K, double* f) const;

 private:
  struct Cell {
    std::array<Index, 4> node;
    std::array<double, 12> gradient;  // 4 x 3, row-major
    double volume;
    std::array<Index, 16> offset;     // column 3 node[b] in row 3 node[a], from the row's start
  };
  std::vector<Cell> cells_;  // in schedule order
  std::vector<std::vector<std::pair<Index, Index>>> phases_;
  double lambda_, mu_;
};

}  // namespace kerf::bench
