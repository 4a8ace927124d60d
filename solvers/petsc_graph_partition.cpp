// solvers/graph_partition.h over PETSc's MatPartitioning: inside the PETSc module.
#include <petscmat.h>

#include <algorithm>

#include "core/check.h"
#include "solvers/petsc_internals.h"

namespace kerf {

std::vector<int> petsc_ptscotch_parts(std::span<const Index> offsets, std::span<const Index> neighbours, int parts) {
  const PetscInt vertices = static_cast<PetscInt>(offsets.size()) - 1;
  KERF_CHECK(vertices >= 0 && parts >= 1, "internal: a graph of ", vertices, " vertices into ", parts, " parts");
  if (parts == 1 || vertices == 0) return std::vector<int>(vertices, 0);
  KERF_CHECK(vertices >= parts, "the mesh has ", vertices, " cells, fewer than the ", parts,
             " ranks it is divided among; expected at least one cell a rank (run on fewer ranks)");
  start_petsc();
  // MatCreateMPIAdj takes arrays from PetscMalloc and frees them with the matrix.
  PetscInt *ia = nullptr, *ja = nullptr;
  petsc_check(PetscMalloc1(vertices + 1, &ia), "PetscMalloc1");
  petsc_check(PetscMalloc1(std::max<std::size_t>(neighbours.size(), 1), &ja), "PetscMalloc1");
  std::copy(offsets.begin(), offsets.end(), ia);
  std::copy(neighbours.begin(), neighbours.end(), ja);
  Mat graph = nullptr;
  MatPartitioning partitioning = nullptr;
  IS part_of = nullptr;
  petsc_check(MatCreateMPIAdj(PETSC_COMM_SELF, vertices, vertices, ia, ja, nullptr, &graph), "MatCreateMPIAdj");
  petsc_check(MatPartitioningCreate(PETSC_COMM_SELF, &partitioning), "MatPartitioningCreate");
  petsc_check(MatPartitioningSetAdjacency(partitioning, graph), "MatPartitioningSetAdjacency");
  petsc_check(MatPartitioningSetType(partitioning, MATPARTITIONINGPTSCOTCH), "MatPartitioningSetType");
  petsc_check(MatPartitioningSetNParts(partitioning, parts), "MatPartitioningSetNParts");
  petsc_check(MatPartitioningApply(partitioning, &part_of), "MatPartitioningApply");
  const PetscInt* part = nullptr;
  petsc_check(ISGetIndices(part_of, &part), "ISGetIndices");
  std::vector<int> out(part, part + vertices);
  petsc_check(ISRestoreIndices(part_of, &part), "ISRestoreIndices");
  petsc_check(ISDestroy(&part_of), "ISDestroy");
  petsc_check(MatPartitioningDestroy(&partitioning), "MatPartitioningDestroy");
  petsc_check(MatDestroy(&graph), "MatDestroy");
  std::vector<Index> count(parts, 0);
  for (int p : out) {
    KERF_CHECK(p >= 0 && p < parts, "internal: PT-Scotch returned part ", p, " of ", parts);
    ++count[p];
  }
  const auto empty = std::find(count.begin(), count.end(), 0);
  KERF_CHECK(empty == count.end(), "PT-Scotch gave rank ", empty - count.begin(), " no cell of the mesh's ", vertices,
             " among ", parts, " ranks; expected a mesh of many more cells than ranks (run on fewer ranks)");
  return out;
}

}  // namespace kerf
