#pragma once
// The equations a stepper integrates: the body's own, plus the terms that live
// on the solver side (contact with rigid spheres), over the body's dofs
// followed by the terms' own (each sphere's translation). Steppers and the
// implicit system see this, never the body alone, so the body knows nothing
// of contact and contact nothing of the method.
#include <memory>
#include <span>

#include "core/rank_share.h"
#include "core/run_report.h"
#include "discretization/discrete_body.h"
#include "solvers/contact_term.h"
#include "solvers/rank_sum.h"
#include "solvers/row_share.h"
#include "solvers/sparse_assembly.h"

namespace kerf {

class MechanicalSystem {
 public:
  /// The body with the scene's contact (none without `contact` in the scene).
  /// Throws when the scene has contact and the body has no surface samples.
  /// `ranks`: this process among the run's MPI ranks (the linear systems'
  /// rows are split between them; a partitioned body's are its own nodes').
  MechanicalSystem(DiscreteBody& body, const Scene& scene, RunReport& report, RankShare ranks = {});

  const DiscreteBody& body() const { return body_; }
  /// This process among the run's MPI ranks.
  const RankShare& ranks() const { return ranks_; }
  /// The body's tangents from now on: definite (projected) or exact (DiscreteBody::use_definite_tangent).
  void use_definite_tangent(bool definite) { body_.use_definite_tangent(definite); }
  /// The body's shape functions changed in place (a growing cut) at the
  /// points whose support holds one of `changed_nodes`: the terms read those again.
  void discretization_changed(std::span<const Index> changed_nodes) {
    if (contact_) contact_->refresh_interpolations(body_, changed_nodes);
  }
  /// An implicit time step starts from u (all dofs): DiscreteBody::begin_time_step.
  void begin_time_step(const Vector& u) {
    Vector buffer;
    body_.begin_time_step(body_part(u, buffer));
  }
  /// The contact term, or null.
  const ContactTerm* contact() const { return contact_.get(); }
  ContactTerm* contact() { return contact_.get(); }

  int dofs_per_node() const { return body_.dofs_per_node(); }
  Index dof_count() const { return body_dofs_ + (contact_ ? contact_->dof_count() : 0); }
  /// Reference position of the node a dof belongs to (a sphere's centre for its dofs).
  Vec3 dof_position(Index dof) const;
  /// The body's part of a vector over all dofs (its dofs come first): x
  /// itself without terms, else copied into `buffer` (no allocation once sized).
  const Vector& body_part(const Vector& x, Vector& buffer) const;

  /// How the MPI ranks share the dofs: a body that assembles its rank's
  /// cells only (PartitionedAssembly) writes partial matrices, which the
  /// solver adds up; its forces, energy and lumped mass are summed here, so
  /// every vector and number this class returns is whole on every rank.
  const RowShare& dof_share() const { return share_; }
  /// Adds the ranks' parts of a vector computed from partial matrices (as
  /// K u); null unless the body is partitioned.
  const RankSum* rank_sum() const { return rank_sum_.get(); }
  /// A partitioned rank's touched nodes (its cells' and its contact points',
  /// each sphere counted as the node after the body's): the rows of its partial matrices.
  const std::vector<Index>& kept_nodes() const { return kept_nodes_; }

  void visit_couplings(const CouplingVisitor& visit) const;
  /// f_int(u) of the body and the terms (N). Not reentrant (kept buffers).
  void internal_force(const Vector& u, Vector& f) const;
  /// Not for a partitioned body (its blocks cannot be summed through a sink).
  void tangent(const Vector& u, const BlockSink& sink, Vector* f) const;
  /// The same added into K (whose pattern is build_pattern's), the body's part
  /// straight into K's arrays when it can (MatrixAssembly); K holds this
  /// rank's part when the body is partitioned, f is whole.
  void tangent_into(const Vector& u, SparseMatrix& K, Vector* f) const;
  /// Linear in u: a linear body without contact.
  bool is_linear() const { return body_.is_linear() && !contact_; }
  /// The body's (contact's terms are symmetric).
  bool symmetric_tangent() const { return body_.symmetric_tangent(); }
  /// The body's Galerkin tangent (its test functions its trial ones) and the
  /// contact terms into K: what preconditions an unsymmetric tangent.
  void galerkin_tangent_into(const Vector& u, SparseMatrix& K) const;
  /// What is known of a dof (a sphere's: which sphere), for a failed solve's message.
  std::string describe_dof(Index dof) const;
  /// A linear body with contact: its stiffness may be assembled once
  /// (body().tangent) and only the terms' part (add_terms) each time.
  bool linear_body_with_terms() const { return body_.is_linear() && contact_; }
  /// The terms' forces added into f, their tangent into *sink when given.
  void add_terms(const Vector& u, Vector& f, const BlockSink* sink) const;
  /// The body's strain energy (J; a contact penalty's is not counted).
  double strain_energy(const Vector& u) const;

  Vector lumped_mass() const;
  /// This rank's part when the body is partitioned (a partial matrix).
  void consistent_mass(const BlockSink& sink) const;
  /// f_ext(t): the body's loads times load_scale(), and the force-driven spheres' forces.
  void external_force(double t, Vector& f) const;
  /// The scene's body force and boundary loads scaled from now on (a session
  /// changing a load between steps; 1 at the start).
  void scale_loads(double factor) { load_scale_ = factor; }
  double load_scale() const { return load_scale_; }
  std::vector<DirichletDof> dirichlet(double t) const;

 private:
  /// The body's tangent at its part of u (and its force into *f when given).
  using BodyTangent = std::function<void(const Vector& body_u, Vector* body_f)>;
  /// The body's tangent, then the terms' (into `sink`); f over all dofs.
  void tangent_with(const BodyTangent& body_tangent, const Vector& u, const BlockSink& sink, Vector* f) const;
  /// The ranks' share of the dofs (share_), and rank_sum_ when the body is partitioned.
  void share_rows();

  DiscreteBody& body_;
  Index body_dofs_;
  RankShare ranks_;  // this process among the run's
  std::unique_ptr<ContactTerm> contact_;
  RowShare share_;
  std::unique_ptr<RankSum> rank_sum_;
  std::vector<Index> kept_nodes_;
  double load_scale_ = 1.0;
  mutable Vector body_u_, body_f_;  // buffers of the calls made every step (internal and external force)
};

/// The pattern of every block the system will write (the body's and the terms').
SparseMatrix build_pattern(const MechanicalSystem& mechanics);

}  // namespace kerf
