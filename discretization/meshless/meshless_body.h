#pragma once
// What the two meshless bodies (EFG, nodal integration) answer alike: nodes,
// selections, point interpolation, surface samples, ParaView snapshots, the
// cuts' lattices and the MLS conditioning all come from their MeshlessDomain;
// loads are dead (assembled once, f_ext = load_); no cheap critical-step bound
// (the stepper's Lanczos bound is used).
#include <optional>
#include <string>
#include <vector>

#include "discretization/body_capabilities.h"
#include "discretization/meshless/integration_constraint.h"
#include "discretization/meshless/meshless_domain.h"
#include "discretization/meshless/weak_boundary_conditions.h"
#include "problem/material.h"

namespace kerf {

class MeshlessBody : public DiscreteBody,
                     public SurfaceSampling,
                     public EnrichmentLattices,
                     public DiscretizationFigures {
 public:
  int dofs_per_node() const override { return domain_.dimension(); }
  Index node_count() const override { return domain_.nodes().size(); }
  Vec3 node_position(Index node) const override { return domain_.nodes().positions[node]; }
  double mean_neighbors() const override { return domain_.mean_neighbors(); }
  bool is_linear() const override { return law_.is_linear(); }
  void use_definite_tangent(bool definite) override { law_.set_definite_tangent(definite); }

  void external_force(double, Vector& f) const override { f = load_; }
  std::vector<DirichletDof> dirichlet(double) const override { return dirichlet_; }

  std::vector<Index> select_nodes(const Selection& s) const override { return domain_.select_nodes(s); }
  std::optional<PointInterpolation> interpolation_at(const Vec3& x) const override {
    return domain_.interpolation_at(x);
  }
  void snapshot(const Vector& u, BodySnapshot& out) const override { domain_.snapshot(u, law_, out); }
  std::vector<LatticeSnapshot> enrichment_lattices() const override { return domain_.enrichment_lattices(); }
  SurfaceSamples surface_samples(const Box& region, int points_per_direction) const override {
    return domain_.surface_samples(region, points_per_direction);
  }

  void add_figures(std::map<std::string, double>& extras) const override {
    const MomentConditioning c = domain_.conditioning();
    extras["mls_condition_median"] = c.median;
    extras["mls_condition_max"] = c.max;
    if (domain_.enrichment()) {
      extras["mls_condition_near_cut_max"] = c.near_cut_max;
      extras["mls_condition_near_tip_max"] = c.near_tip_max;
      extras["mls_reduced_basis_nodes"] = static_cast<double>(c.reduced_basis);
    }
    // The integration constraint, tested as the forces are: the largest
    // residual over set-up and, with VCI, every cut growth.
    extras["ic_residual_max"] = constraint_worst_.max;
    extras["ic_residual_rms"] = constraint_worst_.rms;
    extras["ic_residual_setup_max"] = constraint_setup_.max;
    extras["ic_boundary_points_singular"] = static_cast<double>(domain_.boundary_points_singular());
    if (const WeakBoundaryConditions* weak = weak_conditions(); weak && weak->largest_alpha_growth() > 1.0)
      extras["nitsche_alpha_growth_max"] = weak->largest_alpha_growth();
    if (corrected_) {
      extras["ic_residual_uncorrected_max"] = uncorrected_worst_.max;
      extras["ic_residual_uncorrected_rms"] = uncorrected_worst_.rms;
    }
  }

  const MeshlessDomain& domain() const { return domain_; }

  /// The node, its MLS conditioning and the weak conditions its support reaches.
  std::string describe_dof(Index dof) const override {
    const Index node = dof / dofs_per_node();
    std::string out = DiscreteBody::describe_dof(dof) + ", MLS condition number " +
                      std::to_string(domain_.at_nodes().condition[node]);
    const std::vector<std::int8_t>& reduced = domain_.at_nodes().basis_directions;
    if (!reduced.empty() && reduced[node] >= 0)
      out += "; a cut leaves it " + std::to_string(reduced[node]) +
             " direction(s) of nodes on its side (its basis reduced to them: a piece the cut frees is held by nothing)";
    if (const WeakBoundaryConditions* weak = weak_conditions()) out += weak->describe_node(node);
    return out;
  }

 protected:
  MeshlessBody(const Scene& scene, MeshlessDomain domain)
      : domain_(std::move(domain)), law_(scene.material), density_(scene.material.density),
        gravity_(scene.gravity), boundary_(scene.boundary) {}

  /// The body's weakly imposed conditions (null when none).
  virtual const WeakBoundaryConditions* weak_conditions() const { return nullptr; }

  /// Records the integration constraint's residual as it stands (set-up, a
  /// cut's growth): `tested` with the forces' test gradients, `uncorrected`
  /// with the plain MLS ones when a correction is on (else empty).
  void record_constraint(const ConstraintResidual& tested, std::optional<ConstraintResidual> uncorrected) {
    if (constraint_setup_.worst < 0) constraint_setup_ = tested;
    if (tested.max >= constraint_worst_.max) constraint_worst_ = tested;
    if (!uncorrected) return;
    corrected_ = true;
    if (uncorrected->max >= uncorrected_worst_.max) uncorrected_worst_ = *uncorrected;
  }

  MeshlessDomain domain_;
  MaterialLaw law_;
  double density_;  // kg/m^3
  Vector load_;     // dead loads (N)
  std::vector<DirichletDof> dirichlet_;
  // The loads, integrated again when a growing cut changes their shape functions.
  Vec3 gravity_;                              // m/s^2
  std::vector<BoundaryCondition> boundary_;  // the scene's conditions (tractions and pressures are loads)

 private:
  ConstraintResidual constraint_setup_, constraint_worst_, uncorrected_worst_;
  bool corrected_ = false;
};

}  // namespace kerf
