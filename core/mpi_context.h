#pragma once
// The MPI context of a run, an explicit value handed down from the command
// line (which asks PETSc, solvers/petsc_session.h) to the run and from there
// to the body factory and the mesh: which rank this process is of how many,
// and how rank 0's numbers reach the others, for the layers below the
// solvers that do not know PETSc. The default is a serial run.
#include <utility>
#include <vector>

#include "core/rank_share.h"

namespace kerf {

/// Sends rank 0's numbers to every rank: each rank passes its own (the
/// others' are ignored) and gets rank 0's back. A collective call.
using FirstRankSender = std::vector<double> (*)(std::vector<double>);

struct MpiContext {
  RankShare ranks;                       // this process among the run's
  FirstRankSender send_first = nullptr;  // null in a serial run: nobody to send to

  bool distributed() const { return ranks.distributed(); }
  /// Rank 0's `values` on every rank (a collective call under mpirun).
  std::vector<double> from_first_rank(std::vector<double> values) const {
    return send_first ? send_first(std::move(values)) : values;
  }
};

}  // namespace kerf
