#pragma once
// Which of the MPI ranks this process is, for the code that splits work
// between them without knowing PETSc (the bodies). Set once by the command
// line (solvers/petsc_session.h finds it); 0 of 1 otherwise.
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

/// This process's share, as the command line recorded it.
inline RankShare& process_ranks_storage() {
  static RankShare share;
  return share;
}
inline const RankShare& process_ranks() { return process_ranks_storage(); }
inline void set_process_ranks(RankShare share) { process_ranks_storage() = share; }

/// Sends rank 0's numbers to every rank: each rank passes its own (the
/// others' are ignored) and gets rank 0's back. A collective call. The
/// command line sets PETSc's (solvers/petsc_session.h) under mpirun, so the
/// layers below the solvers can use it without knowing PETSc; unset in a
/// serial run, where there is nobody to send to.
using FirstRankSender = std::vector<double> (*)(std::vector<double>);
inline FirstRankSender& first_rank_sender_storage() {
  static FirstRankSender sender = nullptr;
  return sender;
}
inline void set_first_rank_sender(FirstRankSender sender) { first_rank_sender_storage() = sender; }
inline std::vector<double> from_first_rank(std::vector<double> values) {
  const FirstRankSender sender = first_rank_sender_storage();
  return sender ? sender(std::move(values)) : values;
}

/// [begin, end) of `rank`'s part of n items split as PETSc splits ownership
/// (PetscSplitOwnership): n / count each, one more for the first n % count.
inline std::pair<Index, Index> even_part(Index n, int rank, int count) {
  const Index base = n / count, extra = n % count;
  const Index begin = rank * base + std::min<Index>(rank, extra);
  return {begin, begin + base + (rank < extra ? 1 : 0)};
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
