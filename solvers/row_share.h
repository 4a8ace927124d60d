#pragma once
// How the MPI ranks share the rows of the system's vectors and matrices.
#include <vector>

#include "core/types.h"

namespace kerf {

struct RowShare {
  Index owned_begin = 0, owned_end = 0;  // this rank's rows; the ranks' ranges follow each other
  /// Each rank computed its part of the values from its own cells: the ranks'
  /// parts add up to the matrix (false: every rank holds the whole).
  bool partial = false;
  std::vector<Index> touched;  // partial: the rows this rank computes values in, sorted (its own and ghosts)
  /// Rows come in whole nodes of this many (dofs per node), or 1: PETSc's
  /// algebraic multigrid then aggregates nodes, not single dofs.
  int block_size = 1;
};

}  // namespace kerf
