#pragma once
// Rigid frictionless spheres pressed into a body (the scene's `contact`), the
// same for fem, efg and nodal: a term on the solver side that reads the body's
// surface samples (its SurfaceSampling capability) and writes force and
// tangent through the same sink as the body. Each sphere has dofs of its own,
// after the body's: its translation. A displacement-driven sphere's dofs are
// prescribed. A force-driven one is guided along its force line (its lateral
// reaction, which a quarter model has, goes into the guide): in a static run
// its depth along the force is prescribed too, found by secant steps on the
// contact force (in F^(2/3), which Hertz makes linear in the depth), one per
// augment(); in a dynamic run it moves along its force's axis with its own
// mass (the body's density), pushed by the force.
//
// Non-penetration is imposed at Gauss points of the boundary facets the sphere
// can reach, with the normal traction t_q = <lambda_q + k_q (R - |x_q - c|)>_+
// (Pa) at point q, along the sphere's outward normal n_q. Static runs use an
// augmented Lagrangian (Simo and Laursen 1992), k_q = 100 E / (1 - nu^2) /
// size_q: the static stepper calls augment(), which sets lambda_q = t_q and
// asks for another solve while some point penetrates deeper than 1e-4 of its
// facet's size and 1e-3 of the sphere's travel, or a sphere's force is off by
// more than 1e-4. Dynamic runs use the penalty alone (lambda = 0; updating it
// every step pumped energy into explicit runs): k_q = 100 E* / size_q
// implicit, 10 E* / size_q explicit, which leaves a penetration of about
// p size / k.
//
// On a partitioned body each rank evaluates an even share of each sphere's
// points (forces and tangent blocks into its partial vectors and matrices,
// added by PETSc); the sphere's force and the augmentation's decisions are
// sums over the ranks, so every rank takes the same steps. The sphere's
// rows belong to the last rank, which alone adds its mass.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/rank_share.h"
#include "discretization/body_capabilities.h"
#include "problem/scene.h"
#include "solvers/rank_sum.h"

namespace kerf {

/// Where a rigid indenter stands.
struct ContactReading {
  double indentation = 0.0;          // depth of the sphere below the undeformed surface (m)
  Vec3 force = Vec3::Zero();         // force the sphere exerts on the body (N)
  Vec3 displacement = Vec3::Zero();  // of the sphere's centre (m)
};

class ContactTerm {
 public:
  /// The scene's spheres against the body's surface; their dofs start at
  /// `first_dof` (the body's dof count). Throws, naming the sphere's scene
  /// line, when a sphere cannot reach the body or starts inside it.
  /// Split over `ranks` (a partitioned body), each rank evaluates an even
  /// share of each sphere's points; set_rank_sum then adds their forces.
  ContactTerm(const Scene& scene, const SurfaceSampling& surface, Index first_dof, int dofs_per_node,
              RankShare ranks = {});
  /// Adds the ranks' contact forces in augment() and reading() (collective
  /// calls then: every rank makes them together).
  void set_rank_sum(const RankSum* sum) { rank_sum_ = sum; }
  /// The body nodes this rank's points reach, ascending.
  std::vector<Index> own_point_nodes() const;

  Index sphere_count() const { return static_cast<Index>(spheres_.size()); }
  /// The spheres' dofs: dofs_per_node each, after the body's.
  Index dof_count() const { return dim_ * sphere_count(); }
  /// Reference position of sphere i's centre (m).
  const Vec3& centre(Index sphere) const { return spheres_[sphere].center; }

  void visit_couplings(const CouplingVisitor& visit) const;
  /// The contact forces at u added into f (N, over all dofs), and their
  /// tangent into *sink when given. Not reentrant (kept scratch: every explicit step calls it).
  void add(const Vector& u, Vector& f, const BlockSink* sink) const;
  /// Augmented Lagrangian update at a converged static u under load factor
  /// `load`: true when a constraint is still violated beyond its tolerance, so
  /// the static solve is repeated with the new multipliers and prescribed
  /// positions (a force-driven sphere's depth).
  bool augment(const Vector& u, double load);
  /// What augment() changes (the multipliers, a force-driven sphere's depth
  /// and secant), kept to undo a static increment whose solve failed.
  struct AugmentationState {
    std::vector<std::vector<double>> multipliers;
    std::vector<std::array<double, 3>> depths;  // depth, previous_depth, previous_g
  };
  AugmentationState augmentation_state() const;
  void restore(const AugmentationState& state);
  /// The state of sphere i at u.
  ContactReading reading(Index sphere, const Vector& u) const;
  /// A session's hand on a sphere (dynamic runs; the stepper is then told:
  /// Stepper::applied_changed). A displacement-driven sphere's centre moved
  /// to `displacement` (m) from its reference position; a force-driven one
  /// pushed with `force` (N) from now on. Refused, naming the sphere's scene
  /// line and key, where the sphere would leave the part of the surface
  /// sampled for it (its scene path: within twice its scene displacement of
  /// that path; a force no larger than its scene force, on the same line).
  void move_sphere(Index sphere, const Vec3& displacement);
  void push_sphere(Index sphere, const Vec3& force);
  /// The interpolation of the points whose nodes include one of
  /// `changed_nodes` taken again from the body, whose shape functions a
  /// growing cut changed in place (same points, same multipliers).
  void refresh_interpolations(const DiscreteBody& body, std::span<const Index> changed_nodes);

  /// The spheres' masses into their dofs of `lumped` (kg per dof).
  void fill_lumped_mass(Vector& lumped) const;
  void consistent_mass(const BlockSink& sink) const;
  /// The force-driven spheres' forces into their dofs of f (N).
  void fill_external_force(Vector& f) const;
  /// The spheres' constrained dofs, appended (after the body's: still sorted).
  void append_dirichlet(std::vector<DirichletDof>& out) const;

 private:
  struct Sphere {
    Vec3 center = Vec3::Zero();  // reference (m)
    double radius = 0.0;         // m
    std::optional<Vec3> force, displacement;
    Vec3 travel = Vec3::Zero();  // the scene's path (m): its points were sampled around it
    double largest_force = 0.0;  // N: the scene's force, which set that path
    std::string where;           // the scene line, for messages
    double mass = 0.0;  // kg
    // Force-driven: the unit force direction, the depth along it (m) and the
    // previous (depth, F^(2/3)) of the secant; the half-space depth of the force (m).
    Vec3 direction = Vec3::Zero();
    double depth = 0.0, previous_depth = 0.0, previous_g = -1.0, half_space_depth = 0.0;
    std::vector<SurfacePoint> points;
    std::vector<std::array<Vec3, 3>> facets;  // reference facets near the sphere (indentation)
    std::vector<double> penalty;              // k_q (Pa/m)
    std::vector<double> multiplier;           // lambda_q (Pa)
  };
  /// The contact of one point at u: whether it presses, its traction t (Pa),
  /// normal n (unit, from the centre), distance |x - c| (m), penetration (m).
  struct PointContact {
    bool active = false;
    double traction = 0.0, distance = 0.0, penetration = 0.0;
    Vec3 normal = Vec3::Zero();
  };

  /// Sphere c with its contact points (those of `surface` it can reach), penalties and mass.
  Sphere place(const ContactSphere& c, const SurfaceSampling& surface, const Material& material, double dt) const;
  Index sphere_dof(std::size_t i) const { return first_dof_ + dim_ * static_cast<Index>(i); }
  Vec3 sphere_displacement(std::size_t i, const Vector& u) const;
  PointContact evaluate(const Sphere& s, std::size_t q, const Vec3& centre, const Vector& u) const;
  /// The secant step of a force-driven sphere's depth towards its force.
  void step_depth(Sphere& s, double push, double target, double load) const;

  /// This rank's points of sphere s: [first, second).
  std::pair<std::size_t, std::size_t> own_points(const Sphere& s) const {
    return even_part(static_cast<Index>(s.points.size()), ranks_.rank, ranks_.count);
  }
  /// x added over the ranks (x itself when not split).
  double total(double x) const { return rank_sum_ ? rank_sum_->sum(x) : x; }

  std::vector<Sphere> spheres_;
  Index first_dof_;
  int dim_;
  RankShare ranks_;
  const RankSum* rank_sum_ = nullptr;
  bool explicit_ = false;
  bool static_ = false;  // a static run: the force scales with the load factor
  mutable std::vector<Index> dofs_;           // add()'s scratch: one point's dofs,
  mutable std::vector<double> beta_, block_;  // its coefficients and tangent block
};

}  // namespace kerf
