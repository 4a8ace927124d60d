#include "discretization/meshless/efg_body.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.h"
#include "discretization/fem/simplex_quadrature.h"
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
    : MeshlessBody(scene, std::move(domain)),
      nitsche_(scene.discretization.meshless.essential == EssentialMethod::nitsche),
      points_(make_points(domain_, scene.discretization.meshless.quadrature_order)) {
  stress_.assign(points_.point_count(), Mat3::Zero());
  assemble_loads();
  build_constraints(scene);
  share_points(share);
}

void EfgBody::assemble_loads() {
  const int dim = domain_.dimension();
  load_ = Vector::Zero(dof_count());
  const ShapeTable& t = points_.shapes();
  for (Index p = 0; p < points_.point_count(); ++p) {
    auto near = t.neighbours.of(p);
    const double* phi = t.values_of(p);
    for (std::size_t k = 0; k < near.size(); ++k)
      for (int i = 0; i < dim; ++i) load_[dim * near[k] + i] += density_ * points_.weight(p) * phi[k] * scene_.gravity[i];
  }
  domain_.add_boundary_loads(scene_, load_);
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
  for (WeakConstraint& c : constraints_) {
    std::vector<Index> held;
    for (Index q = 0; q < c.shapes.point_count(); ++q) {
      auto near = c.shapes.neighbours.of(q);
      if (std::any_of(near.begin(), near.end(), [&](Index J) { return moved[J]; })) held.push_back(q);
    }
    domain_.refresh_rows(c.shapes, c.points.position, held, "the boundary quadrature point");
  }
  const bool gravity = scene_.gravity.squaredNorm() > 0.0;
  if ((gravity && update.points > 0) || domain_.boundary_loads_touch(changed)) assemble_loads();
  return update;
}

void EfgBody::share_points(RankShare share) {
  share_ = share;
  const Index per_cell = points_.schedule().group_size, cells = points_.point_count() / per_cell;
  const auto [first_cell, end_cell] = even_part(cells, share.rank, share.count);
  own_points_ = {first_cell * per_cell, end_cell * per_cell};
  own_nodes_ = even_part(node_count(), share.rank, share.count);
  own_schedule_ = only_points(points_.schedule(), own_points_);
  std::vector<char> reached(node_count(), 0);
  for (Index p = own_points_.first; p < own_points_.second; ++p)
    for (Index J : points_.shapes().neighbours.of(p)) reached[J] = 1;
  for (const WeakConstraint& c : constraints_) {
    const auto [begin, end] = own_constraint_points(c);
    for (Index q = begin; q < end; ++q)
      for (Index J : c.shapes.neighbours.of(q)) reached[J] = 1;
  }
  touched_nodes_ = touched_node_list(std::move(reached), own_nodes_);
}

std::pair<Index, Index> EfgBody::own_constraint_points(const WeakConstraint& c) const {
  return even_part(c.shapes.point_count(), share_.rank, share_.count);
}

void EfgBody::build_constraints(const Scene& scene) {
  const int order = scene.discretization.meshless.quadrature_order;
  const double factor = nitsche_ ? nitsche_factor : penalty_factor;
  const NodeSet& nodes = domain_.nodes();
  for (const BoundaryCondition& bc : scene.boundary) {
    if (!bc.is_dirichlet() || bc.select.kind == Selection::Kind::point) continue;
    WeakConstraint c;
    std::vector<Index> facets = domain_.facets_in(bc.select);
    c.points = domain_.boundary_points(facets, order);
    c.shapes = domain_.shapes_at(c.points.position, "the boundary quadrature point");
    const std::size_t per_facet = c.points.position.size() / facets.size();
    for (std::size_t q = 0; q < c.points.position.size(); ++q) {
      c.facet.push_back(facets[q / per_facet]);
      // The finest spacing among the point's nodes: on a graded lattice the
      // mean lets the coarse nodes weaken the term below what Nitsche needs.
      double h = std::numeric_limits<double>::infinity();
      for (Index I : c.shapes.neighbours.of(static_cast<Index>(q))) h = std::min(h, nodes.spacing[I]);
      c.alpha.push_back(factor * law_.p_wave_modulus() / h);
    }
    for (int i = 0; i < domain_.dimension(); ++i) {
      if (!bc.fixed[i] && !bc.displacement[i]) continue;
      c.projection(i, i) = 1.0;
      c.value[i] = bc.fixed[i] ? 0.0 : *bc.displacement[i];
    }
    constraints_.push_back(std::move(c));
  }
  dirichlet_ = domain_.nodal_constraints(
      scene, [](const BoundaryCondition& bc) { return bc.select.kind == Selection::Kind::point; });
}

double EfgBody::constraint_point(const WeakConstraint& c, Index q, const Vector& u, Vector* f,
                                 std::vector<double>* block, std::vector<Mat3>& T) const {
  const int dim = domain_.dimension();
  auto near = c.shapes.neighbours.of(q);
  const Index n = static_cast<Index>(near.size()), size = n * dim;
  const double* phi = c.shapes.values_of(q);
  const double* g = c.shapes.gradients_of(q);
  const double w = c.points.weight[q], alpha = c.alpha[q];
  const Vec3& normal = c.points.normal[q];
  const Vec3 d = c.projection * (interpolated_displacement(c.shapes, q, u) - c.value);
  double energy = 0.5 * w * alpha * d.squaredNorm();
  Vec3 Pn = Vec3::Zero();
  if (nitsche_) {  // T_a(j, i) = (dP/dF : e_i (x) g_a) n, component j
    Mat3 P;
    Mat9 A;
    law_.stress_and_tangent(deformation_gradient(c.shapes, q, u), P, A);
    Pn = c.projection * (P * normal);
    energy -= w * d.dot(P * normal);
    T.assign(n, Mat3::Zero());
    for (Index a = 0; a < n; ++a)
      for (int j = 0; j < dim; ++j)
        for (int i = 0; i < dim; ++i)
          for (int l = 0; l < dim; ++l)
            for (int m = 0; m < dim; ++m) T[a](j, i) += A(j + 3 * l, i + 3 * m) * g[dim * a + m] * normal[l];
  }
  if (f)
    for (Index a = 0; a < n; ++a)
      for (int i = 0; i < dim; ++i) {
        double r = alpha * phi[a] * d[i];
        if (nitsche_) r -= phi[a] * Pn[i] + d.dot(T[a].col(i));
        (*f)[dim * near[a] + i] += w * r;
      }
  if (block)
    for (Index a = 0; a < n; ++a)
      for (Index b = 0; b < n; ++b) {
        Mat3 K = alpha * phi[a] * phi[b] * c.projection;
        if (nitsche_) K -= phi[a] * (c.projection * T[b]) + phi[b] * (c.projection * T[a]).transpose();
        for (int i = 0; i < dim; ++i)
          for (int k = 0; k < dim; ++k) (*block)[(dim * a + i) * size + dim * b + k] += w * K(i, k);
      }
  return energy;
}

double EfgBody::constraint_terms(const Vector& u, Vector* f) const {
  double energy = 0.0;
  std::vector<Mat3> scratch;
  for (const WeakConstraint& c : constraints_) {
    const auto [begin, end] = own_constraint_points(c);
    for (Index q = begin; q < end; ++q) energy += constraint_point(c, q, u, f, nullptr, scratch);
  }
  return energy;
}

void EfgBody::internal_force(const Vector& u, Vector& f) const {
  KERF_CHECK(u.size() == dof_count(), "displacement vector has ", u.size(), " entries; expected ", dof_count());
  // Other ranks' points keep a zero stress (set when the body was made): the gather adds this rank's part.
#pragma omp parallel for schedule(static)
  for (Index p = own_points_.first; p < own_points_.second; ++p)
    stress_[p] = points_.weight(p) * law_.stress(deformation_gradient(points_.shapes(), p, u));
  points_.gather(stress_, f);
  constraint_terms(u, &f);
}

double EfgBody::strain_energy(const Vector& u) const {
  KERF_CHECK(u.size() == dof_count(), "displacement vector has ", u.size(), " entries; expected ", dof_count());
  double energy = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : energy)
  for (Index p = own_points_.first; p < own_points_.second; ++p)
    energy += points_.weight(p) * law_.energy(deformation_gradient(points_.shapes(), p, u));
  return energy + constraint_terms(u, nullptr);
}

void EfgBody::tangent(const Vector& u, const BlockSink& sink, Vector* f) const {
  KERF_CHECK(u.size() == dof_count(), "displacement vector has ", u.size(), " entries; expected ", dof_count());
  assemble_material_blocks(points_.shapes(), own_schedule_, points_.weights(), law_, u, sink);
  std::vector<double> block;
  std::vector<Index> dofs;
  std::vector<Mat3> scratch;
  for (const WeakConstraint& c : constraints_) {
    const auto [begin, end] = own_constraint_points(c);
    for (Index q = begin; q < end; ++q) {
      neighbour_dofs(c.shapes, q, dofs);
      block.assign(dofs.size() * dofs.size(), 0.0);
      constraint_point(c, q, u, nullptr, &block, scratch);
      sink(dofs, block);
    }
  }
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
  for (const WeakConstraint& c : constraints_)
    for (Index q = 0; q < c.shapes.point_count(); ++q) {
      neighbour_dofs(c.shapes, q, dofs);
      visit(dofs);
    }
}

Vector EfgBody::lumped_mass() const {
  // Row sums of the consistent mass: rho int phi_I (the phi_J add up to one).
  const int dim = domain_.dimension();
  Vector m = Vector::Zero(dof_count());
  const ShapeTable& t = points_.shapes();
  for (Index p = own_points_.first; p < own_points_.second; ++p) {
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
  std::vector<Index> facets = domain_.facets_in(selection, false);
  std::vector<char> inside(domain_.facets().count(), 0);
  for (Index f : facets) inside[f] = 1;
  Vec3 total = Vec3::Zero();
  for (const WeakConstraint& c : constraints_)
    for (Index q = 0; q < c.shapes.point_count(); ++q) {
      if (!inside[c.facet[q]]) continue;
      const Vec3 uh = interpolated_displacement(c.shapes, q, u);
      // The force the support exerts: minus the constraint's share of f_int
      // summed over the nodes (the Nitsche adjoint term sums to zero).
      Vec3 force = -c.alpha[q] * (c.projection * (uh - c.value));
      if (nitsche_) force += c.projection * (law_.stress(deformation_gradient(c.shapes, q, u)) * c.points.normal[q]);
      total += c.points.weight[q] * force;
    }
  return total;
}

}  // namespace kerf
