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
#include <vector>

#include "discretization/discrete_body.h"
#include "discretization/meshless/meshless_domain.h"
#include "discretization/meshless/point_integration.h"
#include "problem/material.h"

namespace kerf {

class EfgBody final : public DiscreteBody {
 public:
  /// alpha = factor (lambda + 2 mu) / h, h the local node spacing.
  static constexpr double nitsche_factor = 10.0;
  static constexpr double penalty_factor = 1.0e4;

  EfgBody(const Scene& scene, MeshlessDomain domain);

  int dofs_per_node() const override { return domain_.dimension(); }
  Index node_count() const override { return domain_.nodes().size(); }
  Vec3 node_position(Index node) const override { return domain_.nodes().positions[node]; }
  Index element_count() const override { return points_.point_count(); }
  double mean_neighbors() const override { return domain_.mean_neighbors(); }

  void visit_couplings(const CouplingVisitor& visit) const override;
  /// Not reentrant: two calls on one body must not run at the same time (per-point scratch).
  void internal_force(const Vector& u, Vector& f) const override;
  void tangent(const Vector& u, const BlockSink& sink, Vector* f) const override;
  double strain_energy(const Vector& u) const override;
  bool is_linear() const override { return law_.is_linear(); }

  Vector lumped_mass() const override;
  void consistent_mass(const BlockSink& sink) const override;
  void external_force(double t, Vector& f) const override { f = load_; }
  std::vector<DirichletDof> dirichlet(double) const override { return dirichlet_; }
  std::optional<double> critical_time_step() const override { return std::nullopt; }

  std::vector<Index> select_nodes(const Selection& s) const override { return domain_.select_nodes(s); }
  std::optional<PointInterpolation> interpolation_at(const Vec3& x) const override {
    return domain_.interpolation_at(x);
  }
  void snapshot(const Vector& u, BodySnapshot& out) const override { domain_.snapshot(u, law_, out); }
  void cut_snapshot(const Vector& u, BodySnapshot& out) const override { domain_.cut_snapshot(u, out); }
  std::vector<LatticeSnapshot> enrichment_lattices() const override { return domain_.enrichment_lattices(); }
  Vec3 weak_reaction(const Vector& u, const Selection& selection) const override;

  const MeshlessDomain& domain() const { return domain_; }

 private:
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
  /// rho phi_a phi_b w summed over the integration points, per point (scalar per node pair).
  Eigen::MatrixXd point_mass(Index p) const;

  MeshlessDomain domain_;
  MaterialLaw law_;
  double density_;
  bool nitsche_;
  PointIntegration points_;
  std::vector<WeakConstraint> constraints_;
  Vector load_;
  std::vector<DirichletDof> dirichlet_;
  mutable std::vector<Mat3> stress_;
};

}  // namespace kerf
