#include "discretization/meshless/efg_body.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/check.h"
#include "core/parallel_failure.h"
#include "discretization/csr_block_sink.h"
#include "discretization/meshless/efg_cell_rules.h"
#include "discretization/meshless/integration_constraint.h"
#include "discretization/meshless/point_sums.h"
#include "problem/selection.h"

namespace kerf {
namespace {

struct CellQuadrature {
  std::vector<Vec3> position;
  std::vector<double> weight;
  Index per_cell = 0;
};

/// The scene's rule (efg_cell_rule) on every straight cell of the mesh.
CellQuadrature cell_quadrature(const Mesh& mesh, const MeshlessOptions& options) {
  const int dim = mesh.dimension;
  const QuadratureRule rule = efg_cell_rule(options, dim);
  CellQuadrature out;
  out.per_cell = static_cast<Index>(rule.points.size());
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    auto nodes = mesh.cell(c);
    const Vec3& a = mesh.nodes[nodes[0]];
    Mat3 J = Mat3::Identity();
    for (int k = 0; k < dim; ++k) J.col(k) = mesh.nodes[nodes[k + 1]] - a;
    const double det = std::abs(J.determinant());
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      Vec3 r = rule.points[q];
      if (dim == 2) r.z() = 0.0;
      out.position.push_back(a + J * r);
      out.weight.push_back(rule.weights[q] * det);
    }
  }
  return out;
}

/// Which cells' points a rank integrates: the cell goes to the rank owning
/// most of its points' support nodes (ties: the lowest), so that its blocks
/// fall mostly in that rank's own rows (the ranks' rows are even ranges of the
/// nodes). An even share of the cells in their own order sent half the blocks
/// of a bar to the other rank (the lattice's node order and the cells' order
/// run along different axes): 6.7 million stashed entries a rank, +335 MB, on
/// the scaling study's EFG cantilever. Into `others_reaching_own`: the
/// neighbour lists of the other ranks' points that reach this rank's nodes.
std::vector<char> cells_of_rank(const MeshlessDomain& domain, const CellQuadrature& q, RankShare share,
                                NeighborLists& others_reaching_own) {
  const Index per_cell = q.per_cell, cells = static_cast<Index>(q.position.size()) / per_cell;
  if (!share.distributed()) return std::vector<char>(cells, 1);
  const Index N = domain.nodes().size();
  const auto [own_begin, own_end] = even_part(N, share.rank, share.count);
  constexpr Index chunk = 4096;  // cells whose points' neighbour lists are held at once
  std::vector<char> mine(cells, 0);
  std::vector<Index> votes(share.count);
  for (Index first = 0; first < cells; first += chunk) {
    const Index last = std::min(cells, first + chunk);
    const NeighborLists near = domain.supports_covering(
        std::span<const Vec3>(q.position).subspan(first * per_cell, (last - first) * per_cell), per_cell);
    for (Index c = first; c < last; ++c) {
      std::fill(votes.begin(), votes.end(), 0);
      bool reaches_own = false;
      const Index begin = (c - first) * per_cell, end = begin + per_cell;
      for (Index p = begin; p < end; ++p)
        for (Index J : near.of(p)) {
          ++votes[even_part_owner(N, J, share.count)];
          reaches_own = reaches_own || (J >= own_begin && J < own_end);
        }
      mine[c] = std::max_element(votes.begin(), votes.end()) - votes.begin() == share.rank;
      if (mine[c] || !reaches_own) continue;
      for (Index p = begin; p < end; ++p) {
        auto list = near.of(p);
        others_reaching_own.index.insert(others_reaching_own.index.end(), list.begin(), list.end());
        others_reaching_own.start.push_back(static_cast<Index>(others_reaching_own.index.size()));
      }
    }
  }
  return mine;
}

/// This rank's cells' Gauss points (cells_of_rank) and their shape functions.
PointIntegration rank_points(const MeshlessDomain& domain, const MeshlessOptions& options, RankShare share,
                             NeighborLists& others_reaching_own) {
  CellQuadrature q = cell_quadrature(domain.background(), options);
  const std::vector<char> mine = cells_of_rank(domain, q, share, others_reaching_own);
  if (share.distributed()) {
    Index kept = 0;
    for (std::size_t p = 0; p < q.position.size(); ++p)
      if (mine[p / q.per_cell]) q.position[kept] = q.position[p], q.weight[kept++] = q.weight[p];
    q.position.resize(kept), q.weight.resize(kept);
  }
  ShapeTable shapes = domain.shapes_at(q.position, "the quadrature point", q.per_cell);
  return PointIntegration(std::move(shapes), std::move(q.position), std::move(q.weight), domain.nodes().positions,
                          q.per_cell);
}

}  // namespace

EfgBody::EfgBody(const Scene& scene, MeshlessDomain domain, const MpiContext& mpi)
    : MeshlessBody(scene, std::move(domain)),
      mpi_(mpi),
      points_(rank_points(domain_, scene.discretization.meshless, mpi.ranks, others_reaching_own_)) {
  reduced_basis_points_ =
      static_cast<Index>(mpi_.sum_on_every_rank(static_cast<double>(points_.shapes().reduced_basis_points())));
  stress_.assign(points_.point_count(), Mat3::Zero());
  assemble_loads();
  build_constraints(scene);
  share_nodes();
  record_constraint_residual();
}

WeakBoundaryConditions::VolumePoints EfgBody::volume_points() const {
  return {points_.shapes(), points_.weights(), points_.positions(), mpi_.distributed() ? &mpi_ : nullptr};
}

void EfgBody::build_constraints(const Scene& scene) {
  const EssentialMethod essential = essential_method(scene.discretization.meshless, Method::efg);
  if (essential == EssentialMethod::parameters) {
    dirichlet_ = domain_.nodal_constraints(scene, [](const BoundaryCondition&) { return true; });
    return;
  }
  const QuadratureRule facet_rule = efg_facet_rule(scene.discretization.meshless, domain_.dimension());
  constraints_ = std::make_unique<WeakBoundaryConditions>(scene, domain_, law_, essential == EssentialMethod::nitsche,
                                                          facet_rule, volume_points());
  dirichlet_ = domain_.nodal_constraints(
      scene, [](const BoundaryCondition& bc) { return bc.select.kind == Selection::Kind::point; });
}

void EfgBody::record_constraint_residual() {
  VolumeTerms volume = volume_terms(points_.shapes(), points_.weights(), node_count());
  for (std::vector<double>* sum : {&volume.gradient_sum, &volume.magnitude, &volume.value_sum})
    mpi_.sum_on_every_rank(*sum);
  record_constraint(constraint_residual(domain_.boundary_terms(), volume, domain_.dimension()), std::nullopt);
}

void EfgBody::assemble_loads() {
  const int dim = domain_.dimension();
  load_ = Vector::Zero(dof_count());
  if (gravity_.squaredNorm() > 0.0) {
    const ShapeTable& t = points_.shapes();
    std::vector<double> gravity_load(dim * node_count(), 0.0);
    add_over_points(points_.point_count(), gravity_load, [&](Index p, double* sums) {
      auto near = t.neighbours.of(p);
      const double* phi = t.values_of(p);
      for (std::size_t k = 0; k < near.size(); ++k)
        for (int i = 0; i < dim; ++i) sums[dim * near[k] + i] += density_ * points_.weight(p) * phi[k] * gravity_[i];
    });
    load_ = Eigen::Map<const Vector>(gravity_load.data(), dof_count());
    mpi_.sum_on_every_rank(std::span<double>(load_.data(), load_.size()));
  }
  domain_.add_boundary_loads(boundary_, load_);  // every boundary point, on every rank
}

CutUpdate EfgBody::update_for_cuts(double t) {
  // Every rank brings its own points' rows up to t; the neighbour lists, hence
  // the schedule and each rank's points and touched rows, stay. The nodes'
  // table (output, probes) and the boundary points' are whole on every rank.
  CutUpdate update;
  const std::vector<Index> changed = domain_.update_shapes_for_cuts(t);  // the same on every rank
  if (changed.empty()) return update;
  update.nodes = static_cast<Index>(changed.size());
  update.changed_nodes = changed;
  const std::vector<Index> rows =
      domain_.rows_the_growth_may_change(points_.shapes(), points_.positions(), points_.points_holding(changed));
  std::array<double, 2> counts{
      static_cast<double>(
          domain_.refresh_rows(points_.shapes_in_place(), points_.positions(), rows, "the quadrature point").size()),
      static_cast<double>(points_.shapes().reduced_basis_points())};
  mpi_.sum_on_every_rank(counts);
  update.points = static_cast<Index>(counts[0]);
  reduced_basis_points_ = static_cast<Index>(counts[1]);
  std::vector<char> moved(node_count(), 0);
  for (Index I : changed) moved[I] = 1;
  if (constraints_) constraints_->update_for_cuts(domain_, moved, volume_points());
  const bool gravity = gravity_.squaredNorm() > 0.0;
  if ((gravity && update.points > 0) || domain_.boundary_loads_touch(changed)) assemble_loads();
  return update;
}

void EfgBody::begin_time_step(const Vector& u) {
  if (constraints_) constraints_->refresh_alpha(u, volume_points());
}

void EfgBody::share_nodes() {
  const RankShare share = mpi_.ranks;
  own_nodes_ = even_part(node_count(), share.rank, share.count);
  std::vector<char> reached(node_count(), 0);
  for (Index J : points_.shapes().neighbours.index) reached[J] = 1;
  if (constraints_) {
    constraints_->share(share);
    constraints_->mark_reached(reached);
  }
  touched_nodes_ = touched_node_list(std::move(reached), own_nodes_);
}

void EfgBody::internal_force(const Vector& u, Vector& f) const {
  KERF_CHECK(u.size() == dof_count(), "displacement vector has ", u.size(), " entries; expected ", dof_count());
  const Index count = points_.point_count();
#pragma omp parallel for schedule(static)
  for (Index p = 0; p < count; ++p)
    stress_[p] = points_.weight(p) * law_.stress(deformation_gradient(points_.shapes(), p, u));
  points_.gather(stress_, f);
  if (constraints_) constraints_->terms(u, &f);
}

double EfgBody::strain_energy(const Vector& u) const {
  KERF_CHECK(u.size() == dof_count(), "displacement vector has ", u.size(), " entries; expected ", dof_count());
  double energy = 0.0;
  const Index count = points_.point_count();
#pragma omp parallel for schedule(static) reduction(+ : energy)
  for (Index p = 0; p < count; ++p)
    energy += points_.weight(p) * law_.energy(deformation_gradient(points_.shapes(), p, u));
  return energy + (constraints_ ? constraints_->terms(u, nullptr) : 0.0);
}

void EfgBody::tangent(const Vector& u, const BlockSink& sink, Vector* f) const {
  KERF_CHECK(u.size() == dof_count(), "displacement vector has ", u.size(), " entries; expected ", dof_count());
  assemble_material_blocks(points_.shapes(), points_.schedule(), points_.weights(), law_, u, sink);
  if (constraints_) constraints_->add_tangent(u, sink);
  if (f) internal_force(u, *f);
}

void EfgBody::add_tangent_into(const Vector& u, const CsrView& matrix, Vector* f) const {
  KERF_CHECK(u.size() == dof_count(), "displacement vector has ", u.size(), " entries; expected ", dof_count());
  point_tangents(u);
  points_.add_stiffness_rows(tangents_, matrix);
  if (constraints_) constraints_->add_tangent(u, add_into(matrix, 1.0, domain_.dimension()));
  if (f) internal_force(u, *f);
}

void EfgBody::point_tangents(const Vector& u) const {
  if (law_.is_linear()) {  // the same dP/dF everywhere
    Mat3 P;
    tangents_.resize(1);
    law_.stress_and_tangent(Mat3::Identity(), P, tangents_[0]);
    return;
  }
  const Index count = points_.point_count();
  tangents_.resize(count);
  ParallelFailure failure;
#pragma omp parallel for schedule(static)
  for (Index p = 0; p < count; ++p)
    failure.run([&] {
      Mat3 P;
      law_.stress_and_tangent(deformation_gradient(points_.shapes(), p, u), P, tangents_[p]);
    });
  failure.rethrow_if_failed();
}

void EfgBody::visit_couplings(const CouplingVisitor& visit) const {
  std::vector<Index> dofs;
  for (Index p = 0; p < points_.point_count(); ++p) {
    neighbour_dofs(points_.shapes(), p, dofs);
    visit(dofs);
  }
  const int dim = domain_.dimension();
  for (Index p = 0; p < others_reaching_own_.size(); ++p) {
    dofs.clear();
    for (Index J : others_reaching_own_.of(p))
      for (int i = 0; i < dim; ++i) dofs.push_back(dim * J + i);
    visit(dofs);
  }
  // Boundary points couple nodes whose supports reach the boundary: all of
  // them are neighbours of some cell point too, but say so explicitly.
  if (constraints_) constraints_->visit_couplings(visit);
}

Vector EfgBody::lumped_mass() const {
  // Row sums of the consistent mass: rho int phi_I (the phi_J add up to one).
  const int dim = domain_.dimension();
  Vector m = Vector::Zero(dof_count());
  const ShapeTable& t = points_.shapes();
  for (Index p = 0; p < points_.point_count(); ++p) {
    auto near = t.neighbours.of(p);
    const double* phi = t.values_of(p);
    for (std::size_t k = 0; k < near.size(); ++k)
      for (int i = 0; i < dim; ++i) m[dim * near[k] + i] += density_ * points_.weight(p) * phi[k];
  }
  return m;
}

void EfgBody::consistent_mass(const BlockSink& sink) const {
  assemble_mass_blocks(points_.shapes(), points_.schedule(), points_.weights(), density_, sink);
}

Vec3 EfgBody::weak_reaction(const Vector& u, const Selection& selection) const {
  return constraints_ ? constraints_->reaction(u, selection) : Vec3::Zero();
}

void EfgBody::add_figures(std::map<std::string, double>& extras) const {
  MeshlessBody::add_figures(extras);
  if (domain_.enrichment())
    extras["mls_reduced_basis_points"] = static_cast<double>(reduced_basis_points_);
}

}  // namespace kerf
