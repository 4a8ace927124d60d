#pragma once
// Where an explicit stepper keeps its vectors. On one rank, or with contact,
// over every dof (MechanicalSystem's vectors, summed over the ranks by
// RankSum). When each rank computes its own part of the body (a mesh divided
// among the ranks, or a partitioned body whole on every rank), over this
// rank's piece alone: its own dofs, then its ghosts' (the dofs its cells or
// points reach that other ranks own). A step then sends only the ghosts'
// forces between the ranks that share them (solvers/ghost_exchange.h), and
// its vector work is the piece's length.
#include <memory>
#include <span>
#include <vector>

#include "solvers/mechanical_system.h"

namespace kerf {

class ExplicitLayout {
 public:
  virtual ~ExplicitLayout() = default;
  /// Whether the vectors are the piece's (else every dof's, the SolverState's own).
  virtual bool piece() const = 0;
  /// Entries of the layout's vectors.
  virtual Index size() const = 0;
  /// f_int(u), complete at every entry. Collective.
  virtual void internal_force(const Vector& u, Vector& f) const = 0;
  /// The lumped mass, complete at every entry. Collective.
  virtual Vector lumped_mass() const = 0;
  virtual void external_force(double t, Vector& f) const = 0;
  /// The constrained dofs as the layout's entries.
  virtual std::vector<DirichletDof> constrained(const std::vector<DirichletDof>& whole) const = 0;
  /// sum x_i^2 w_i over every dof of the run, each counted once. Collective.
  virtual double weighted_square(const Vector& x, const Vector& w) const = 0;
  /// Whether x is finite on every rank. Collective.
  virtual bool all_finite(const Vector& x) const = 0;
  /// A piece's x as the whole vector over every dof, into `whole` (the whole
  /// layout's vectors are the state's own: nothing to do). The same call on every rank.
  virtual void to_whole(const Vector& x, Vector& whole) const = 0;
  /// The same at the whole vector's entries `dofs` alone (ascending, the same list on every rank).
  virtual void to_whole_at(const Vector& x, std::span<const Index> dofs, Vector& whole) const = 0;
};

/// The piece's layout when the body has one (PieceLayout) or is partitioned
/// (PartitionedAssembly), and no solver-side terms (contact); else the whole one.
std::unique_ptr<ExplicitLayout> explicit_layout(const MechanicalSystem& mechanics);

}  // namespace kerf
