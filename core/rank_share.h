#pragma once
// A share of the MPI ranks: a body given one computes only its rank's part
// (RankShare{} is the whole, as in a serial run). Which rank this process is
// comes with the run's MpiContext (core/mpi_context.h), never from a global.
#include <algorithm>
#include <utility>
#include <vector>

#include "core/types.h"

namespace kerf {

struct RankShare {
  int rank = 0;
  int count = 1;
  bool distributed() const { return count > 1; }
};

/// [begin, end) of `rank`'s part of n items split as PETSc splits ownership
/// (PetscSplitOwnership): n / count each, one more for the first n % count.
inline std::pair<Index, Index> even_part(Index n, int rank, int count) {
  const Index base = n / count, extra = n % count;
  const Index begin = rank * base + std::min<Index>(rank, extra);
  return {begin, begin + base + (rank < extra ? 1 : 0)};
}

/// The rank whose even_part of n items holds item i.
inline int even_part_owner(Index n, Index i, int count) {
  const Index base = n / count, extra = n % count, long_items = extra * (base + 1);
  return static_cast<int>(i < long_items ? i / (base + 1) : extra + (i - long_items) / base);
}

/// A rank's touched nodes: those its own cells or points reach (`reached`,
/// one mark a node) and its owned range, ascending.
inline std::vector<Index> touched_node_list(std::vector<char> reached, std::pair<Index, Index> owned) {
  std::fill(reached.begin() + owned.first, reached.begin() + owned.second, 1);
  std::vector<Index> nodes;
  for (Index n = 0; n < static_cast<Index>(reached.size()); ++n)
    if (reached[n]) nodes.push_back(n);
  return nodes;
}

}  // namespace kerf
