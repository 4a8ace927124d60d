#pragma once
// A graph divided into parts by PETSc's MatPartitioning with PT-Scotch, the
// one partitioner Debian's PETSc is built with (no ParMETIS, METIS or Chaco):
// used on a mesh's cell graph, on one rank, before the mesh is divided among the ranks.
#include <span>
#include <vector>

#include "core/types.h"

namespace kerf {

/// The part (0 .. parts - 1) of each vertex of the graph (CSR: `offsets`,
/// vertices + 1 entries, into `neighbours`: each vertex's neighbours sorted,
/// itself not among them, the graph symmetric). PT-Scotch balances the
/// vertices' counts and cuts few edges; the same graph gives the same parts
/// on every run. Every part non-empty when vertices >= parts. Not collective
/// (PETSC_COMM_SELF).
std::vector<int> ptscotch_parts(std::span<const Index> offsets, std::span<const Index> neighbours, int parts);

}  // namespace kerf
