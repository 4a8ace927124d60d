#pragma once
// Vectors laid out as a rank's piece of a divided mesh holds them: its own
// entries (one contiguous range of the global numbering, the ranks' ranges
// in rank order) followed by its ghosts' (entries other ranks own that its
// cells touch). Through a PETSc ghosted vector (VecCreateGhost): an entry
// summed over the ranks crosses only between the ranks that share it, not
// the whole vector to every rank as RankSum's does (in the PETSc module:
// solvers/petsc_module.h). Collective calls.
#include <memory>
#include <span>
#include <vector>

#include "core/types.h"
#include "solvers/rank_numbers.h"

namespace kerf {

class GhostExchange {
 public:
  /// `own_count` entries from this rank's range, then `ghosts` (global
  /// numbers of entries other ranks own), out of `global_size`.
  GhostExchange(Index global_size, Index own_count, std::span<const Index> ghosts);
  ~GhostExchange();
  GhostExchange(const GhostExchange&) = delete;
  GhostExchange& operator=(const GhostExchange&) = delete;

  Index local_size() const { return own_count_ + ghost_count_; }
  Index own_count() const { return own_count_; }

  /// `local` holds this rank's parts (own and ghost entries); on return each
  /// entry, own or ghost, holds the sum of every rank's part of it (the
  /// owner's sum, copied to the ghosts: equal to the last bit).
  void sum_and_share(Vector& local) const;
  /// The sum of every rank's x.
  double sum(double x) const { return numbers_.sum(x); }
  /// The whole vector's entries at `entries` (global numbers, ascending, the
  /// same list on every rank), written into `whole` (sized global_size; its
  /// other entries untouched), from every rank's own entries of `local`. Its
  /// scatter is kept while the list stays the same (a run's probes).
  void gather(const Vector& local, std::span<const Index> entries, Vector& whole) const;
  /// Every entry of the whole vector on every rank.
  void gather_all(const Vector& local, Vector& whole) const;

  /// What exchanges the entries (the PETSc module's), sized as this exchange.
  class Engine {
   public:
    virtual ~Engine() = default;
    virtual void sum_and_share(Vector& local) const = 0;
    virtual void gather(const Vector& local, std::span<const Index> entries, Vector& whole) const = 0;
    virtual void gather_all(const Vector& local, Vector& whole) const = 0;
  };

 private:
  Index own_count_, ghost_count_;
  std::unique_ptr<Engine> engine_;
  RankNumbers numbers_;
};

}  // namespace kerf
