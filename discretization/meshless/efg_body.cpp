#include "discretization/meshless/efg_body.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.h"
#include "discretization/fem/simplex_quadrature.h"
#include "discretization/meshless/integration_constraint.h"
#include "problem/selection.h"

namespace kerf {
namespace {

struct CellQuadrature {
  std::vector<Vec3> position;
  std::vector<double> weight;
  Index per_cell = 0;
};

/// Collapsed Gauss points (n per direction) on every straight cell of the mesh.
CellQuadrature cell_quadrature(const Mesh& mesh, int n) {
  const int dim = mesh.dimension;
  QuadratureRule rule = collapsed_gauss(dim, n);
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

PointIntegration make_points(const MeshlessDomain& domain, int order) {
  CellQuadrature q = cell_quadrature(domain.background(), order);
  ShapeTable shapes = domain.shapes_at(q.position, "the quadrature point");
  return PointIntegration(std::move(shapes), std::move(q.position), std::move(q.weight), domain.nodes().positions,
                          q.per_cell);
}

}  // namespace

EfgBody::EfgBody(const Scene& scene, MeshlessDomain domain, RankShare share)
    : MeshlessBody(scene, std::move(domain)), points_(make_points(domain_, scene.discretization.meshless.quadrature_order)) {
  stress_.assign(points_.point_count(), Mat3::Zero());
  assemble_loads();
  build_constraints(scene);
  share_points(share);
  record_constraint_residual();
}

void EfgBody::build_constraints(const Scene& scene) {
  const EssentialMethod essential = essential_method(scene.discretization.meshless, Method::efg);
  if (essential == EssentialMethod::parameters) {
    dirichlet_ = domain_.nodal_constraints(scene, [](const BoundaryCondition&) { return true; });
    return;
  }
  constraints_ = std::make_unique<WeakBoundaryConditions>(
      scene, domain_, law_, essential == EssentialMethod::nitsche, scene.discretization.meshless.quadrature_order,
      WeakBoundaryConditions::VolumePoints{points_.shapes(), points_.weights(), points_.positions()});
  dirichlet_ = domain_.nodal_constraints(
      scene, [](const BoundaryCondition& bc) { return bc.select.kind == Selection::Kind::point; });
}

void EfgBody::record_constraint_residual() {
  const VolumeTerms volume = volume_terms(points_.shapes(), points_.weights(), node_count());
  record_constraint(constraint_residual(domain_.boundary_terms(), volume, domain_.dimension()), std::nullopt);
}

void EfgBody::assemble_loads() {
  const int dim = domain_.dimension();
  load_ = Vector::Zero(dof_count());
  const ShapeTable& t = points_.shapes();
  for (Index p = 0; p < points_.point_count(); ++p) {
    auto near = t.neighbours.of(p);
    const double* phi = t.values_of(p);
    for (std::size_t k = 0; k < near.size(); ++k)
      for (int i = 0; i < dim; ++i) load_[dim * near[k] + i] += density_ * points_.weight(p) * phi[k] * gravity_[i];
  }
  domain_.add_boundary_loads(boundary_, load_);
}

CutUpdate EfgBody::update_for_cuts(double t) {
  // Every rank brings every table up to t (the same on each): the neighbour
  // lists, hence the schedule and each rank's points and touched rows, stay.
  CutUpdate update;
  const std::vector<Index> changed = domain_.update_shapes_for_cuts(t);  // the nodes' own (output, probes)
  if (changed.empty()) return update;
  update.nodes = static_cast<Index>(changed.size());
  const std::vector<Index> rows = points_.points_holding(changed);
  update.points = static_cast<Index>(
      domain_.refresh_rows(points_.shapes_in_place(), points_.positions(), rows, "the quadrature point").size());
  std::vector<char> moved(node_count(), 0);
  for (Index I : changed) moved[I] = 1;
  if (constraints_)
    constraints_->update_for_cuts(
        domain_, moved, WeakBoundaryConditions::VolumePoints{points_.shapes(), points_.weights(), points_.positions()});
  const bool gravity = gravity_.squaredNorm() > 0.0;
  if ((gravity && update.points > 0) || domain_.boundary_loads_touch(changed)) assemble_loads();
  return update;
}

void EfgBody::begin_time_step(const Vector& u) {
  if (constraints_)
    constraints_->refresh_alpha(
        u, WeakBoundaryConditions::VolumePoints{points_.shapes(), points_.weights(), points_.positions()});
}

std::vector<char> EfgBody::cells_of_this_rank() const {
  const Index per_cell = points_.schedule().group_size, cells = points_.point_count() / per_cell;
  if (!share_.distributed()) return std::vector<char>(cells, 1);
  // The ranks' rows are even ranges of the nodes; a cell goes to the rank
  // owning most of its points' support nodes (ties: the lowest), so that its
  // blocks fall mostly in that rank's own rows. An even share of the cells
  // in their own order sent half the blocks of a bar to the other rank (the
  // lattice's node order and the cells' order run along different axes):
  // 6.7 million stashed entries a rank, +335 MB, on the scaling study's EFG cantilever.
  std::vector<char> mine(cells, 0);
  std::vector<Index> votes(share_.count);
  for (Index c = 0; c < cells; ++c) {
    std::fill(votes.begin(), votes.end(), 0);
    for (Index p = c * per_cell; p < (c + 1) * per_cell; ++p)
      for (Index J : points_.shapes().neighbours.of(p))
        ++votes[even_part_owner(node_count(), J, share_.count)];
    mine[c] = std::max_element(votes.begin(), votes.end()) - votes.begin() == share_.rank;
  }
  return mine;
}

void EfgBody::share_points(RankShare share) {
  share_ = share;
  const Index per_cell = points_.schedule().group_size;
  KERF_CHECK(points_.point_count() % per_cell == 0, "internal: ", points_.point_count(), " points in cells of ",
             per_cell);
  own_nodes_ = even_part(node_count(), share.rank, share.count);
  const std::vector<char> own_cells = cells_of_this_rank();
  own_points_.clear();
  for (Index p = 0; p < points_.point_count(); ++p)
    if (own_cells[p / per_cell]) own_points_.push_back(p);
  own_schedule_ = only_groups(points_.schedule(), own_cells);
  std::vector<char> reached(node_count(), 0);
  for (Index p : own_points_)
    for (Index J : points_.shapes().neighbours.of(p)) reached[J] = 1;
  if (constraints_) {
    constraints_->share(share);
    constraints_->mark_reached(reached);
  }
  touched_nodes_ = touched_node_list(std::move(reached), own_nodes_);
}

void EfgBody::internal_force(const Vector& u, Vector& f) const {
  KERF_CHECK(u.size() == dof_count(), "displacement vector has ", u.size(), " entries; expected ", dof_count());
  // Other ranks' points keep a zero stress (set when the body was made): the gather adds this rank's part.
  const Index own = static_cast<Index>(own_points_.size());
#pragma omp parallel for schedule(static)
  for (Index k = 0; k < own; ++k) {
    const Index p = own_points_[k];
    stress_[p] = points_.weight(p) * law_.stress(deformation_gradient(points_.shapes(), p, u));
  }
  points_.gather(stress_, f);
  if (constraints_) constraints_->terms(u, &f);
}

double EfgBody::strain_energy(const Vector& u) const {
  KERF_CHECK(u.size() == dof_count(), "displacement vector has ", u.size(), " entries; expected ", dof_count());
  double energy = 0.0;
  const Index own = static_cast<Index>(own_points_.size());
#pragma omp parallel for schedule(static) reduction(+ : energy)
  for (Index k = 0; k < own; ++k)
    energy += points_.weight(own_points_[k]) * law_.energy(deformation_gradient(points_.shapes(), own_points_[k], u));
  return energy + (constraints_ ? constraints_->terms(u, nullptr) : 0.0);
}

void EfgBody::tangent(const Vector& u, const BlockSink& sink, Vector* f) const {
  KERF_CHECK(u.size() == dof_count(), "displacement vector has ", u.size(), " entries; expected ", dof_count());
  assemble_material_blocks(points_.shapes(), own_schedule_, points_.weights(), law_, u, sink);
  if (constraints_) constraints_->add_tangent(u, sink);
  if (f) internal_force(u, *f);
}

void EfgBody::visit_couplings(const CouplingVisitor& visit) const {
  std::vector<Index> dofs;
  for (Index p = 0; p < points_.point_count(); ++p) {
    neighbour_dofs(points_.shapes(), p, dofs);
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
  for (Index p : own_points_) {
    auto near = t.neighbours.of(p);
    const double* phi = t.values_of(p);
    for (std::size_t k = 0; k < near.size(); ++k)
      for (int i = 0; i < dim; ++i) m[dim * near[k] + i] += density_ * points_.weight(p) * phi[k];
  }
  return m;
}

void EfgBody::consistent_mass(const BlockSink& sink) const {
  assemble_mass_blocks(points_.shapes(), own_schedule_, points_.weights(), density_, sink);
}

Vec3 EfgBody::weak_reaction(const Vector& u, const Selection& selection) const {
  return constraints_ ? constraints_->reaction(u, selection) : Vec3::Zero();
}

void EfgBody::add_figures(std::map<std::string, double>& extras) const {
  MeshlessBody::add_figures(extras);
  if (domain_.enrichment())
    extras["mls_reduced_basis_points"] = static_cast<double>(points_.shapes().reduced_basis_points());
}

}  // namespace kerf
