#pragma once
// What the two meshless bodies (EFG, nodal integration) answer alike: nodes,
// selections, point interpolation, surface samples, ParaView snapshots, the
// cuts' lattices and the MLS conditioning all come from their MeshlessDomain;
// loads are dead (assembled once, f_ext = load_); no cheap critical-step bound
// (the stepper's Lanczos bound is used).
#include <vector>

#include "discretization/body_capabilities.h"
#include "discretization/meshless/meshless_domain.h"
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
    }
  }

  const MeshlessDomain& domain() const { return domain_; }

 protected:
  MeshlessBody(const Scene& scene, MeshlessDomain domain)
      : domain_(std::move(domain)), law_(scene.material, scene.solve.tangent == TangentKind::definite), density_(scene.material.density),
        scene_(scene) {}

  MeshlessDomain domain_;
  MaterialLaw law_;
  double density_;  // kg/m^3
  Vector load_;     // dead loads (N)
  std::vector<DirichletDof> dirichlet_;
  Scene scene_;  // the loads, integrated again when a growing cut changes their shape functions
};

}  // namespace kerf
