#pragma once
// Element-free Galerkin: MLS shape functions, the weak form integrated by
// collapsed Gauss rules (meshless.quadrature.order points per direction) on the
// cells of a background mesh, consistent mass. MLS does not interpolate, so
// fix/displacement on planes and boxes are imposed weakly on the boundary faces:
//   penalty:  E_c = alpha/2 int |Pi (u - u_bar)|^2
//   nitsche:  E_c = -int (u - u_bar) . Pi P(F) n + alpha/2 int |Pi (u - u_bar)|^2
// (Pi keeps the constrained components). The Nitsche form is consistent: the
// exact solution satisfies the discrete equations, so the patch test passes to
// round-off. Its tangent drops the term (u - u_bar) . dA/dF, which vanishes
// for linear materials (exact tangent) and is small where the constraint
// holds. `point` selections constrain the nearest node's parameter.
#include <utility>
#include <vector>

#include "core/rank_share.h"
#include "discretization/meshless/meshless_body.h"
#include "discretization/meshless/point_integration.h"
#include "problem/material.h"

namespace kerf {

class EfgBody final : public MeshlessBody,
                      public WeakConstraints,
                      public CutsInShapeFunctions,
                      public PartitionedAssembly {
 public:
  /// alpha = factor (lambda + 2 mu) / h, h the local node spacing.
  static constexpr double nitsche_factor = 10.0;
  static constexpr double penalty_factor = 1.0e4;

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

  /// The rows a growing cut's new pieces touch: the Gauss points', the weak
  /// constraints' boundary points' and, where they changed, the loads.
  CutUpdate update_for_cuts(double t) override;

 private:
  /// Gravity through the Gauss points' shape functions, and the boundary loads, into load_.
  void assemble_loads();
  /// Boundary quadrature points of one weakly imposed condition.
  struct WeakConstraint {
    BoundaryPoints points;
    ShapeTable shapes;
    std::vector<Index> facet;  // per point: the background facet it lies on
    std::vector<double> alpha; // per point (Pa/m)
    Mat3 projection = Mat3::Zero();  // Pi: 1 on the constrained components
    Vec3 value = Vec3::Zero();       // u_bar (m)
  };
  /// The constraint's contribution at boundary point q: residual into f (when
  /// given), tangent block into `block` over the point's neighbours (when
  /// given); returns its energy. `T` is scratch, reused between points.
  double constraint_point(const WeakConstraint& c, Index q, const Vector& u, Vector* f,
                          std::vector<double>* block, std::vector<Mat3>& T) const;
  double constraint_terms(const Vector& u, Vector* f) const;
  void build_constraints(const Scene& scene);
  /// This rank's boundary points of `c`: [begin, end).
  std::pair<Index, Index> own_constraint_points(const WeakConstraint& c) const;
  void share_points(RankShare share);

  bool nitsche_;
  PointIntegration points_;
  RankShare share_;
  std::pair<Index, Index> own_points_, own_nodes_;  // all of them in a serial run
  std::vector<Index> touched_nodes_;                // the nodes its points reach and its own, sorted
  PointSchedule own_schedule_;                      // its points' part of points_.schedule()
  std::vector<WeakConstraint> constraints_;
  mutable std::vector<Mat3> stress_;
};

}  // namespace kerf
