#pragma once
// Rigid frictionless spheres pressed into a body (the scene's `contact`), the
// same for fem, efg and nodal: the body is wrapped, and each sphere becomes
// one more node whose dofs are the sphere's translation. A displacement-driven
// sphere's dofs are prescribed. A force-driven one is guided along its force
// line (its lateral reaction, which a quarter model has, goes into the
// guide): in a static run its depth along the force is prescribed too, found
// by secant steps on the contact force (in F^(2/3), which Hertz makes linear
// in the depth), one per augment(); in a dynamic run it moves along its force's
// axis with its own mass (the body's density), pushed by the force.
//
// Non-penetration is imposed at Gauss points of the boundary facets the sphere
// can reach, with the normal traction t_q = <lambda_q + k_q (R - |x_q - c|)>_+
// (Pa) at point q, along the sphere's outward normal n_q. Static runs use an
// augmented Lagrangian (Simo and Laursen 1992), k_q = 100 E / (1 - nu^2) /
// size_q: augment() sets lambda_q = t_q and asks for another solve while some
// point penetrates deeper than 1e-4 of its facet's size and 1e-3 of the
// sphere's travel, or a sphere's force is off by more than 1e-4. Dynamic runs
// use the penalty alone (lambda = 0; updating it every step pumped energy
// into explicit runs): k_q = 100 E* / size_q implicit, 10 E* / size_q
// explicit, which leaves a penetration of about p size / k.
#include <memory>
#include <vector>

#include "discretization/discrete_body.h"

namespace kerf {

class ContactBody final : public DiscreteBody {
 public:
  ContactBody(const Scene& scene, std::unique_ptr<DiscreteBody> body);

  const DiscreteBody& inner() const { return *body_; }
  /// Contact points of sphere i (for tests).
  const std::vector<SurfacePoint>& contact_points(int sphere) const { return spheres_[sphere].points; }

  int dofs_per_node() const override { return body_->dofs_per_node(); }
  Index node_count() const override { return body_->node_count() + static_cast<Index>(spheres_.size()); }
  Vec3 node_position(Index node) const override;
  void visit_couplings(const CouplingVisitor& visit) const override;
  void internal_force(const Vector& u, Vector& f) const override;
  void tangent(const Vector& u, const BlockSink& sink, Vector* f) const override;
  /// The body's strain energy (the penalty's is not counted).
  double strain_energy(const Vector& u) const override { return body_->strain_energy(inner_part(u)); }
  bool is_linear() const override { return false; }
  const DiscreteBody* linear_part() const override { return body_->is_linear() ? body_.get() : nullptr; }
  void add_nonlinear_part(const Vector& u, Vector& f, const BlockSink* sink) const override;
  bool augment(const Vector& u, double t) override;
  std::optional<ContactReading> contact_reading(int index, const Vector& u) const override;

  Vector lumped_mass() const override;
  void consistent_mass(const BlockSink& sink) const override;
  void external_force(double t, Vector& f) const override;
  std::vector<DirichletDof> dirichlet(double t) const override;
  std::optional<double> critical_time_step() const override { return body_->critical_time_step(); }
  void add_diagnostics(std::map<std::string, double>& counters) const override { body_->add_diagnostics(counters); }

  std::vector<Index> select_nodes(const Selection& selection) const override { return body_->select_nodes(selection); }
  std::optional<PointInterpolation> interpolation_at(const Vec3& x) const override { return body_->interpolation_at(x); }
  void snapshot(const Vector& u, BodySnapshot& out) const override { body_->snapshot(inner_part(u), out); }
  void cut_snapshot(const Vector& u, BodySnapshot& out) const override { body_->cut_snapshot(inner_part(u), out); }
  std::vector<LatticeSnapshot> enrichment_lattices() const override { return body_->enrichment_lattices(); }
  Vec3 weak_reaction(const Vector& u, const Selection& selection) const override {
    return body_->weak_reaction(inner_part(u), selection);
  }
  SurfaceSamples surface_samples(const Box& region, int points_per_direction) const override {
    return body_->surface_samples(region, points_per_direction);
  }
  Index element_count() const override { return body_->element_count(); }
  double mean_neighbors() const override { return body_->mean_neighbors(); }

 private:
  struct Sphere {
    Vec3 center = Vec3::Zero();  // reference (m)
    double radius = 0.0;         // m
    std::optional<Vec3> force, displacement;
    double mass = 0.0;              // kg
    // Force-driven: the unit force direction, the depth along it (m) and the
    // previous (depth, F^(2/3)) of the secant; the half-space depth of the force (m).
    Vec3 direction = Vec3::Zero();
    double depth = 0.0, previous_depth = 0.0, previous_g = -1.0, half_space_depth = 0.0;
    std::vector<SurfacePoint> points;
    std::vector<std::array<Vec3, 3>> facets;  // reference facets near the sphere (indentation)
    std::vector<double> penalty;     // k_q (Pa/m)
    std::vector<double> multiplier;  // lambda_q (Pa)
  };
  /// The contact of one point at u: whether it presses, its traction t (Pa),
  /// normal n (unit, from the centre), distance |x - c| (m), penetration (m).
  struct PointContact {
    bool active = false;
    double traction = 0.0, distance = 0.0, penetration = 0.0;
    Vec3 normal = Vec3::Zero();
  };

  Vector inner_part(const Vector& u) const { return u.head(body_->dof_count()); }
  Index sphere_node(std::size_t i) const { return body_->node_count() + static_cast<Index>(i); }
  Vec3 sphere_displacement(std::size_t i, const Vector& u) const;
  PointContact evaluate(const Sphere& s, std::size_t q, const Vec3& centre, const Vector& u) const;

  std::unique_ptr<DiscreteBody> body_;
  std::vector<Sphere> spheres_;
  mutable Vector inner_u_, inner_f_;  // internal_force's buffers (not for concurrent calls)
  bool explicit_ = false;
  bool static_ = false;  // a static run: the force scales with the load factor
  int dim_;
};

}  // namespace kerf
