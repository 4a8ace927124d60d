#include "solvers/mechanical_system.h"

#include <algorithm>
#include <iterator>

#include "core/check.h"
#include "core/rank_share.h"
#include "discretization/body_capabilities.h"

namespace kerf {

MechanicalSystem::MechanicalSystem(DiscreteBody& body, const Scene& scene, RunReport& report, RankShare ranks)
    : body_(body), body_dofs_(body.dof_count()), ranks_(ranks) {
  if (!scene.contact.empty()) {
    ScopedTimer timer(report.phases, Phase::setup);
    const SurfaceSampling* surface = capability<SurfaceSampling>(body);
    KERF_CHECK(surface, scene.contact.front().where.describe(),
               ": this discretization has no surface samples, so nothing can touch it");
    const PartitionedAssembly* part = capability<PartitionedAssembly>(body);
    const RankShare points = part && part->partitioned() ? ranks_ : RankShare{};
    contact_ = std::make_unique<ContactTerm>(scene, *surface, body_dofs_, body.dofs_per_node(), points);
    report.add_stage("contact");
  }
  share_rows();
}

void MechanicalSystem::share_rows() {
  const int dim = dofs_per_node();
  const PartitionedAssembly* part = capability<PartitionedAssembly>(body_);
  const RankShare& ranks = ranks_;
  if (part && part->partitioned()) {
    // Rows: the body's own nodes; the spheres' (after the body's) the last rank's.
    share_.owned_begin = dim * part->owned_nodes().first;
    share_.owned_end = ranks.rank + 1 == ranks.count ? dof_count() : dim * part->owned_nodes().second;
    kept_nodes_ = part->touched_nodes();
    if (contact_) {
      // This rank's contact points reach their nodes and every sphere.
      std::vector<Index> reached = contact_->own_point_nodes();
      for (Index i = 0; i < contact_->sphere_count(); ++i) reached.push_back(body_.node_count() + i);
      std::vector<Index> merged;
      std::set_union(kept_nodes_.begin(), kept_nodes_.end(), reached.begin(), reached.end(),
                     std::back_inserter(merged));
      kept_nodes_ = std::move(merged);
    }
    for (Index n : kept_nodes_)
      for (int i = 0; i < dim; ++i) share_.touched.push_back(dim * n + i);
    share_.partial = true;
    rank_sum_ = std::make_unique<RankSum>(dof_count(), share_.owned_begin, share_.owned_end, share_.touched);
    if (contact_) contact_->set_rank_sum(rank_sum_.get());
    return;
  }
  // Every rank holds the whole; rows split by nodes, the terms' dofs to the last rank.
  auto [begin, end] = even_part(body_.node_count(), ranks.rank, ranks.count);
  share_.owned_begin = dim * begin;
  share_.owned_end = ranks.rank + 1 == ranks.count ? dof_count() : dim * end;
}

Vec3 MechanicalSystem::dof_position(Index dof) const {
  const int dim = dofs_per_node();
  return dof < body_dofs_ ? body_.node_position(dof / dim) : contact_->centre((dof - body_dofs_) / dim);
}

std::string MechanicalSystem::describe_dof(Index dof) const {
  if (dof < body_dofs_) return body_.describe_dof(dof);
  const int dim = dofs_per_node();
  return "dof " + std::to_string(dof) + ": the translation of contact sphere " + std::to_string((dof - body_dofs_) / dim) +
         ", component " + "xyz"[(dof - body_dofs_) % dim];
}

void MechanicalSystem::visit_couplings(const CouplingVisitor& visit) const {
  body_.visit_couplings(visit);
  if (contact_) contact_->visit_couplings(visit);
}

const Vector& MechanicalSystem::body_part(const Vector& x, Vector& buffer) const {
  if (!contact_) return x;
  buffer = x.head(body_dofs_);
  return buffer;
}

double MechanicalSystem::strain_energy(const Vector& u) const {
  Vector buffer;
  const double energy = body_.strain_energy(body_part(u, buffer));
  return rank_sum_ ? rank_sum_->sum(energy) : energy;
}

void MechanicalSystem::internal_force(const Vector& u, Vector& f) const {
  if (!contact_) {
    body_.internal_force(u, f);
  } else {
    body_.internal_force(body_part(u, body_u_), body_f_);
    f.resize(dof_count());
    f.head(body_dofs_) = body_f_;
    f.tail(dof_count() - body_dofs_).setZero();
    contact_->add(u, f, nullptr);
  }
  if (rank_sum_) rank_sum_->sum(f);
}

void MechanicalSystem::tangent(const Vector& u, const BlockSink& sink, Vector* f) const {
  KERF_CHECK(!rank_sum_, "internal: a partitioned body's tangent through a sink (its parts cannot be added)");
  tangent_with([&](const Vector& body_u, Vector* body_f) { body_.tangent(body_u, sink, body_f); }, u, sink, f);
}

void MechanicalSystem::tangent_into(const Vector& u, SparseMatrix& K, Vector* f) const {
  const BlockSink sink = add_into(K, 1.0, dofs_per_node());
  if (const MatrixAssembly* direct = capability<MatrixAssembly>(body_)) {
    const CsrView view = csr_view(K);
    tangent_with([&](const Vector& body_u, Vector* body_f) { direct->add_tangent_into(body_u, view, body_f); }, u,
                 sink, f);
  } else {
    tangent_with([&](const Vector& body_u, Vector* body_f) { body_.tangent(body_u, sink, body_f); }, u, sink, f);
  }
  if (rank_sum_ && f) rank_sum_->sum(*f);  // K stays this rank's part: the solver adds the parts
}

void MechanicalSystem::galerkin_tangent_into(const Vector& u, SparseMatrix& K) const {
  const BlockSink sink = add_into(K, 1.0, dofs_per_node());
  tangent_with([&](const Vector& body_u, Vector* body_f) {
    body_.galerkin_tangent(body_u, sink);
    if (body_f) body_.internal_force(body_u, *body_f);
  }, u, sink, nullptr);
}

void MechanicalSystem::tangent_with(const BodyTangent& body_tangent, const Vector& u, const BlockSink& sink,
                                    Vector* f) const {
  if (!contact_) return body_tangent(u, f);
  Vector body_u, body_f;
  body_tangent(body_part(u, body_u), &body_f);
  Vector all = Vector::Zero(dof_count());
  all.head(body_dofs_) = body_f;
  contact_->add(u, all, &sink);
  if (f) *f = std::move(all);
}

void MechanicalSystem::add_terms(const Vector& u, Vector& f, const BlockSink* sink) const {
  if (contact_) contact_->add(u, f, sink);
}

Vector MechanicalSystem::lumped_mass() const {
  Vector m = Vector::Zero(dof_count());
  m.head(body_dofs_) = body_.lumped_mass();
  if (rank_sum_) rank_sum_->sum(m);  // the spheres' masses are whole on every rank: after the sum
  if (contact_) contact_->fill_lumped_mass(m);
  return m;
}

void MechanicalSystem::consistent_mass(const BlockSink& sink) const {
  body_.consistent_mass(sink);
  if (contact_) contact_->consistent_mass(sink);
}

void MechanicalSystem::external_force(double t, Vector& f) const {
  if (!contact_) {
    body_.external_force(t, f);
    if (load_scale_ != 1.0) f *= load_scale_;
    return;
  }
  body_.external_force(t, body_f_);
  f.resize(dof_count());
  f.head(body_dofs_) = load_scale_ * body_f_;
  f.tail(dof_count() - body_dofs_).setZero();
  contact_->fill_external_force(f);
}

std::vector<DirichletDof> MechanicalSystem::dirichlet(double t) const {
  std::vector<DirichletDof> out = body_.dirichlet(t);
  if (contact_) contact_->append_dirichlet(out);
  return out;
}

SparseMatrix build_pattern(const MechanicalSystem& mechanics) {
  // A partial matrix needs its touched rows alone (whole, so that the owned ones preallocate PETSc's).
  const bool partial = mechanics.dof_share().partial;
  return build_pattern(mechanics.dofs_per_node(), mechanics.dof_count(),
                       [&](const CouplingVisitor& visit) { mechanics.visit_couplings(visit); },
                       partial ? std::span<const Index>(mechanics.kept_nodes()) : std::span<const Index>());
}

}  // namespace kerf
