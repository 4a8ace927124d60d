#pragma once
// Element-free Galerkin: MLS shape functions, the weak form integrated on the
// cells of a background mesh by the scene's rule (efg_cell_rules.h: collapsed
// Gauss or symmetric), consistent mass. MLS does not interpolate, so
// fix/displacement on planes and boxes are imposed weakly on the boundary
// faces (weak_boundary_conditions.h: Nitsche or penalty), or, with `essential:
// parameters`, on the nodal parameters of the selected nodes; `point`
// selections constrain the nearest node's parameter.
#include <utility>
#include <vector>

#include "core/mpi_context.h"
#include "discretization/meshless/meshless_body.h"
#include "discretization/meshless/point_integration.h"
#include "discretization/meshless/weak_boundary_conditions.h"
#include "problem/material.h"

namespace kerf {

class EfgBody final : public MeshlessBody,
                      public WeakConstraints,
                      public CutsInShapeFunctions,
                      public PartitionedAssembly,
                      public MatrixAssembly {
 public:
  /// Among MPI ranks (`mpi`) the body computes this rank's part alone
  /// (PartitionedAssembly): it owns the rows of an even split of the nodes and
  /// holds the shape functions of its own cells' Gauss points only (a cell is
  /// the rank's that owns most of its points' support nodes), and of each
  /// constraint's boundary points its share. Collective under MPI.
  EfgBody(const Scene& scene, MeshlessDomain domain, const MpiContext& mpi = {});

  bool partitioned() const override { return mpi_.distributed(); }
  std::pair<Index, Index> owned_nodes() const override { return own_nodes_; }
  const std::vector<Index>& touched_nodes() const override { return touched_nodes_; }

  /// Every rank's Gauss points.
  Index element_count() const override {
    return domain_.background().cell_count() * points_.points_per_group();
  }
  /// This rank's Gauss points (every point in a serial run), cell by cell.
  const PointIntegration& points() const { return points_; }

  /// This rank's points' couplings, and those of the other ranks' points that
  /// reach its own nodes: its rows' whole pattern.
  void visit_couplings(const CouplingVisitor& visit) const override;
  /// Not reentrant: two calls on one body must not run at the same time (per-point scratch).
  void internal_force(const Vector& u, Vector& f) const override;
  void tangent(const Vector& u, const BlockSink& sink, Vector* f) const override;
  /// The material part node by node (PointIntegration::add_stiffness_rows:
  /// `matrix` must hold a symmetric matrix before, zero as the solvers pass
  /// it), the weak constraints' through a sink on it. Not reentrant.
  void add_tangent_into(const Vector& u, const CsrView& matrix, Vector* f) const override;
  double strain_energy(const Vector& u) const override;

  Vector lumped_mass() const override;
  void consistent_mass(const BlockSink& sink) const override;

  Vec3 weak_reaction(const Vector& u, const Selection& selection) const override;
  const WeakBoundaryConditions* weak_conditions() const override { return constraints_.get(); }

  /// The rows a growing cut's new pieces touch: each rank's Gauss points', the
  /// weak constraints' boundary points' and, where they changed, the loads
  /// (summed over the ranks). Collective under MPI.
  CutUpdate update_for_cuts(double t) override;
  /// Nitsche's alpha from the tangents at u (WeakBoundaryConditions::refresh_alpha). Collective under MPI.
  void begin_time_step(const Vector& u) override;

  /// The meshless figures, and the Gauss points a cut left a reduced basis (every rank's).
  void add_figures(std::map<std::string, double>& extras) const override;

 private:
  /// Gravity through the Gauss points' shape functions (every rank's, summed), and the boundary loads, into load_.
  void assemble_loads();
  void build_constraints(const Scene& scene);
  void share_nodes();
  /// The integration constraint's residual now (Gauss points: no correction), over every rank's points.
  void record_constraint_residual();
  /// The law's dP/dF at each point at u, into tangents_ (one for a linear law).
  void point_tangents(const Vector& u) const;
  /// This rank's points as the weak constraints see them (with the ranks, to add up their sums).
  WeakBoundaryConditions::VolumePoints volume_points() const;

  MpiContext mpi_;
  // Declared before points_, which fills it as it is made: the neighbour
  // lists of the other ranks' Gauss points that reach this rank's own nodes.
  NeighborLists others_reaching_own_;
  PointIntegration points_;                         // this rank's cells' Gauss points
  Index reduced_basis_points_ = 0;                  // every rank's points a cut left a reduced basis
  std::pair<Index, Index> own_nodes_;               // its rows: every node in a serial run
  std::vector<Index> touched_nodes_;                // the nodes its points reach and its own, sorted
  std::unique_ptr<WeakBoundaryConditions> constraints_;  // null with essential: parameters
  mutable std::vector<Mat3> stress_;                // per point of points_
  mutable std::vector<Mat9> tangents_;              // per point of points_, or one for a linear law
};

}  // namespace kerf
