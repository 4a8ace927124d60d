#pragma once
// Element-free Galerkin: MLS shape functions, the weak form integrated by
// collapsed Gauss rules (meshless.quadrature.order points per direction) on the
// cells of a background mesh, consistent mass. MLS does not interpolate, so
// fix/displacement on planes and boxes are imposed weakly on the boundary
// faces (weak_boundary_conditions.h: Nitsche or penalty), or, with `essential:
// parameters`, on the nodal parameters of the selected nodes; `point`
// selections constrain the nearest node's parameter.
#include <utility>
#include <vector>

#include "core/rank_share.h"
#include "discretization/meshless/meshless_body.h"
#include "discretization/meshless/point_integration.h"
#include "discretization/meshless/weak_boundary_conditions.h"
#include "problem/material.h"

namespace kerf {

class EfgBody final : public MeshlessBody,
                      public WeakConstraints,
                      public CutsInShapeFunctions,
                      public PartitionedAssembly {
 public:
  /// With `share` across ranks the body computes this rank's part alone
  /// (PartitionedAssembly): the Gauss points of an even split of the
  /// locality-ordered background cells and of each constraint's boundary
  /// points; it owns the rows of an even split of the nodes.
  EfgBody(const Scene& scene, MeshlessDomain domain, RankShare share = {});

  bool partitioned() const override { return share_.distributed(); }
  std::pair<Index, Index> owned_nodes() const override { return own_nodes_; }
  const std::vector<Index>& touched_nodes() const override { return touched_nodes_; }

  Index element_count() const override { return points_.point_count(); }
  /// The Gauss points of the cells, cell by cell.
  const PointIntegration& points() const { return points_; }

  void visit_couplings(const CouplingVisitor& visit) const override;
  /// Not reentrant: two calls on one body must not run at the same time (per-point scratch).
  void internal_force(const Vector& u, Vector& f) const override;
  void tangent(const Vector& u, const BlockSink& sink, Vector* f) const override;
  double strain_energy(const Vector& u) const override;

  Vector lumped_mass() const override;
  void consistent_mass(const BlockSink& sink) const override;

  Vec3 weak_reaction(const Vector& u, const Selection& selection) const override;
  const WeakBoundaryConditions* weak_conditions() const override { return constraints_.get(); }

  /// The rows a growing cut's new pieces touch: the Gauss points', the weak
  /// constraints' boundary points' and, where they changed, the loads.
  CutUpdate update_for_cuts(double t) override;
  /// Nitsche's alpha from the tangents at u (WeakBoundaryConditions::refresh_alpha).
  void begin_time_step(const Vector& u) override;

  /// The meshless figures, and the Gauss points a cut left a reduced basis.
  void add_figures(std::map<std::string, double>& extras) const override;

 private:
  /// Gravity through the Gauss points' shape functions, and the boundary loads, into load_.
  void assemble_loads();
  void build_constraints(const Scene& scene);
  void share_points(RankShare share);
  /// The integration constraint's residual now (Gauss points: no correction).
  void record_constraint_residual();

  PointIntegration points_;
  RankShare share_;
  /// The background cells whose points this rank integrates: those most of
  /// whose points' support nodes are its own (set per cell: every cell in a serial run).
  std::vector<char> cells_of_this_rank() const;

  std::vector<Index> own_points_;                   // ascending: every point in a serial run
  std::pair<Index, Index> own_nodes_;               // its rows: every node in a serial run
  std::vector<Index> touched_nodes_;                // the nodes its points reach and its own, sorted
  PointSchedule own_schedule_;                      // its points' part of points_.schedule()
  std::unique_ptr<WeakBoundaryConditions> constraints_;  // null with essential: parameters
  mutable std::vector<Mat3> stress_;
};

}  // namespace kerf
