#pragma once
// The MPI context of a run, an explicit value handed down from the command
// line (which asks PETSc, solvers/petsc_session.h) to the run and from there
// to the body factory and the mesh: which rank this process is of how many,
// and the few collective calls the layers below the solvers need without
// knowing PETSc (rank 0's numbers to every rank, each rank its own part of
// rank 0's numbers, every rank's numbers to all or added up, a graph divided into parts).
// solvers/rank_messages.h makes one whose calls go through PETSc. The
// default is a serial run.
#include <span>
#include <utility>
#include <vector>

#include "core/rank_share.h"
#include "core/types.h"

namespace kerf {

/// Sends rank 0's numbers to every rank: each rank passes its own (the
/// others' are ignored) and gets rank 0's back. A collective call.
using FirstRankSender = std::vector<double> (*)(std::vector<double>);
/// Rank 0 passes one list of numbers per rank (the others pass none); each
/// rank gets its own list. A collective call.
using PartSender = std::vector<double> (*)(std::vector<std::vector<double>>);
/// Every rank's numbers, in rank order, on every rank. A collective call.
using EveryRankGatherer = std::vector<std::vector<double>> (*)(std::vector<double>);
/// Every rank's values (the same length on each) added up, in place, on
/// every rank. A collective call.
using EveryRankSummer = void (*)(std::span<double>);
/// The part (0 .. parts - 1) of each vertex of a graph given as sorted
/// neighbour lists without the vertex itself (CSR: `offsets`, vertices + 1
/// entries, into `neighbours`), each part about as heavy and the edges
/// between parts few. Called on one rank alone.
using GraphPartitioner = std::vector<int> (*)(std::span<const Index> offsets, std::span<const Index> neighbours,
                                              int parts);

struct MpiContext {
  RankShare ranks;                       // this process among the run's
  FirstRankSender send_first = nullptr;  // null in a serial run: nobody to send to
  PartSender send_parts = nullptr;
  EveryRankGatherer gather = nullptr;
  GraphPartitioner partition = nullptr;
  EveryRankSummer summer = nullptr;

  bool distributed() const { return ranks.distributed(); }
  /// Rank 0's `values` on every rank (a collective call under mpirun).
  std::vector<double> from_first_rank(std::vector<double> values) const {
    return send_first ? send_first(std::move(values)) : values;
  }
  /// This rank's list of rank 0's `parts` (a collective call under mpirun;
  /// serial: the only part).
  std::vector<double> part_from_first_rank(std::vector<std::vector<double>> parts) const {
    if (send_parts) return send_parts(std::move(parts));
    return parts.empty() ? std::vector<double>{} : std::move(parts.front());
  }
  /// Every rank's `mine` in rank order (serial: mine alone).
  std::vector<std::vector<double>> from_every_rank(std::vector<double> mine) const {
    if (gather) return gather(std::move(mine));
    return {std::move(mine)};
  }
  /// Every rank's `values` added up, on every rank (serial: as they are).
  void sum_on_every_rank(std::span<double> values) const {
    if (summer) summer(values);
  }
  /// Every rank's x added up (serial: x).
  double sum_on_every_rank(double x) const {
    sum_on_every_rank(std::span<double>(&x, 1));
    return x;
  }
};

}  // namespace kerf
