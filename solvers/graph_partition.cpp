#include "solvers/graph_partition.h"

#include "solvers/petsc_module.h"

namespace kerf {

std::vector<int> ptscotch_parts(std::span<const Index> offsets, std::span<const Index> neighbours, int parts) {
  return petsc_module().ptscotch_parts(offsets, neighbours, parts);
}

}  // namespace kerf
