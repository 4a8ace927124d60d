#pragma once
// Adds up, across the MPI ranks, what each rank computed from its own cells:
// a vector over all dofs of which a rank touches only some entries (its rows
// and its ghosts'), and a number. Every rank gets the whole sum. Through
// PETSc (a parallel vector assembled with ADD_VALUES, then gathered to all):
// kerf passes no message of its own, and PETSc is the PETSc module's
// (solvers/petsc_module.h).
#include <memory>
#include <vector>

#include "core/rank_share.h"
#include "core/types.h"
#include "solvers/rank_numbers.h"

namespace kerf {

class RankSum {
 public:
  /// `size` entries, of which this rank owns [owned_begin, owned_end) (the
  /// ranks' ranges follow each other in rank order) and adds `touched`.
  RankSum(Index size, Index owned_begin, Index owned_end, const std::vector<Index>& touched);
  ~RankSum();
  RankSum(const RankSum&) = delete;
  RankSum& operator=(const RankSum&) = delete;

  /// v holds this rank's part (zero outside `touched`); on return, the sum of every rank's.
  void sum(Vector& v) const;
  double sum(double x) const { return numbers_.sum(x); }
  /// The smallest of every rank's x.
  double smallest(double x) const { return numbers_.smallest(x); }

  /// What sums the vectors (the PETSc module's).
  class Engine {
   public:
    virtual ~Engine() = default;
    virtual void sum(Vector& v) const = 0;
  };

 private:
  RankNumbers numbers_;
  std::unique_ptr<Engine> engine_;
};

/// Every rank's `mine` (the same length on each), in rank order. Collective:
/// every rank must call it.
std::vector<std::vector<double>> values_of_every_rank(const std::vector<double>& mine, const RankShare& ranks);

}  // namespace kerf
