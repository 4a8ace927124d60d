#pragma once
// fix/displacement conditions on planes and boxes imposed weakly on the
// boundary faces, for the meshless bodies (MLS does not interpolate: a
// constraint on the nodal parameters leaves the boundary itself free to move
// by a boundary layer a support wide):
//   penalty:  E_c = int alpha/2 |Pi (u - u_bar)|^2
//   nitsche:  E_c = int -(u - u_bar) . Pi P(F) n + alpha/2 |Pi (u - u_bar)|^2
// (Pi keeps the constrained components). Nitsche's form is consistent: the
// exact solution satisfies the discrete equations, so patch tests pass to
// round-off. Its tangent drops the term (u - u_bar) . dA/dF, which vanishes
// for linear materials (exact tangent) and is small where the constraint holds.
//
// Nitsche's alpha on each boundary face comes from a local estimate, not a
// fixed multiple of E / h. The form stays positive definite when alpha > 2 C,
// C the largest ratio of sum_b w_b |Pi sigma(v) n|^2 (over the constrained
// points) to the strain energy a(v, v). kerf takes, for each node k a face's
// points reach, the ratio for its single parameters (v = e_i at k: the
// traction they make on every constrained point, over K's diagonal at
// rest, the largest over i), the largest over the face's nodes, times
// `meshless.nitsche_safety`. That single-parameter quotient is a lower
// bound of C, so the safety is measured, not proven. A nonlinear law
// estimates it again at the start of each implicit time step with its
// tangents there (refresh_alpha). The least that held:
// on an organ-like body (curved .msh, 4 and 2 mm) 2 for nodal integration
// and 4-8 for EFG; on the cracked plate 8-16 (EFG); on the tissue-sag slab
// 2-4 (EFG) and above 16 (nodal). The default is 32 (problem/scene.h).
// Coarse bodies stiffen with it (EFG on the organ at 4 mm: -3.5% at 8,
// -7.5% at 32; the plate's crack opening moved 2e-4 from 16 to 100);
// coarse nodal integration near a clamp too
// (-6% at 4 mm on the organ where 2 gave +0.2%), and alpha bounds the
// explicit step. A fixed 10 (lambda + 2 mu) / h made EFG's matrix
// indefinite on the organ's 2 mm mesh. The factorization's failure names
// the node and the key when it still happens.
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/mpi_context.h"
#include "core/rank_share.h"
#include "discretization/discrete_body.h"
#include "discretization/meshless/meshless_domain.h"
#include "problem/material.h"

namespace kerf {

class WeakBoundaryConditions {
 public:
  /// alpha = penalty_factor (lambda + 2 mu) / h (penalty; h the finest spacing a point reaches).
  static constexpr double penalty_factor = 1.0e4;

  /// The body's integration points, for Nitsche's estimate: shape functions,
  /// weights (m^3; 2D: m^2) and positions (m). Under MPI (`ranks`) each rank
  /// holds its share of the points, and the estimate's sums over them are
  /// added up across the ranks (collective).
  struct VolumePoints {
    const ShapeTable& table;
    std::span<const double> weight;
    std::span<const Vec3> position;
    const MpiContext* ranks = nullptr;
  };

  /// The scene's fix/displacement conditions on planes and boxes (`point`
  /// selections are left to nodal constraints), `facet_rule` on each face.
  WeakBoundaryConditions(const Scene& scene, const MeshlessDomain& domain, const MaterialLaw& law, bool nitsche,
                         const QuadratureRule& facet_rule, const VolumePoints& volume);

  /// The constraints reaching node `node`, for a failed factorization's
  /// message: which scene items, how (Nitsche or penalty), their alpha; "" when none.
  std::string describe_node(Index node) const;

  bool empty() const { return constraints_.empty(); }
  /// This rank's share of each condition's points (all of them in a serial run).
  void share(RankShare share) { share_ = share; }

  /// Energy of this rank's points; their forces added into f when given.
  /// Not reentrant (scratch).
  double terms(const Vector& u, Vector* f) const;
  /// The tangent blocks of this rank's points into the sink.
  void add_tangent(const Vector& u, const BlockSink& sink) const;
  void visit_couplings(const CouplingVisitor& visit) const;
  /// Marks the nodes this rank's points reach.
  void mark_reached(std::vector<char>& reached) const;
  /// The force the condition's faces inside `selection` exert on the body (N).
  Vec3 reaction(const Vector& u, const Selection& selection) const;
  /// A cut grew: the rows of points reaching one of `changed` nodes are
  /// recomputed, and Nitsche's alpha estimated again from `volume` (as a body
  /// made with the grown cut would have it).
  void update_for_cuts(const MeshlessDomain& domain, std::span<const char> changed, const VolumePoints& volume);
  /// Nitsche with a nonlinear law, at the start of a time step from u: alpha
  /// estimated again with the law's tangents at u (boundary and volume
  /// points), never below its estimate at rest. The material stiffens as it
  /// deforms (neo-Hookean under compression), and an alpha set at rest let
  /// EFG's form go indefinite as the soft block swung under gravity. The
  /// energy does not change within a step. At u = 0 alpha is the rest one.
  void refresh_alpha(const Vector& u, const VolumePoints& volume);

  double smallest_alpha() const, largest_alpha() const;
  /// The largest alpha over its rest value refresh_alpha set so far (1: never raised).
  double largest_alpha_growth() const { return largest_growth_; }

 private:
  struct Constraint {
    BoundaryPoints points;
    ShapeTable shapes;
    std::vector<Index> facet;   // per point: the boundary facet it lies on
    std::vector<double> alpha;  // per point (Pa/m)
    std::vector<double> rest_alpha;  // Nitsche: alpha estimated at rest, per point (Pa/m)
    Mat3 projection = Mat3::Zero();  // Pi: 1 on the constrained components
    Vec3 value = Vec3::Zero();       // u_bar (m)
    SourceLocation where;            // the scene's boundary item
  };
  /// Point q's forces on its neighbours (dim each) into `force`; returns its energy.
  double point_force(const Constraint& c, Index q, const Vector& u, double* force) const;
  /// Point q's tangent block over its neighbours added into `block` (T: scratch).
  void point_tangent(const Constraint& c, Index q, const Vector& u, std::vector<double>& block,
                     std::vector<Mat3>& T) const;
  std::pair<Index, Index> own_points(const Constraint& c) const;
  void set_nitsche_alpha(const VolumePoints& volume);
  /// Per node: its parameters' largest quotient pull / diagonal (both per dof).
  std::vector<double> node_quotients(const std::vector<double>& pull, const std::vector<double>& diagonal) const;
  /// Each face's points take safety_ times the largest quotient of the nodes they reach.
  void set_face_alpha(const std::vector<double>& quotient);
  double safety_ = 1.0;  // Nitsche's alpha over its estimate
  double largest_growth_ = 1.0;  // refresh_alpha's largest alpha / rest alpha

  const MeshlessDomain& domain_;
  const MaterialLaw& law_;
  bool nitsche_;
  RankShare share_;
  std::vector<Constraint> constraints_;
  mutable std::vector<double> forces_;  // terms(): each point's forces, before they are added up
};

}  // namespace kerf
