#include "discretization/meshless/weak_boundary_conditions.h"

#include <algorithm>
#include <limits>
#include <sstream>

#include "core/check.h"
#include "core/parallel_failure.h"
#include "discretization/meshless/point_integration.h"

namespace kerf {

WeakBoundaryConditions::WeakBoundaryConditions(const Scene& scene, const MeshlessDomain& domain, const MaterialLaw& law,
                                               bool nitsche, const QuadratureRule& facet_rule,
                                               const VolumePoints& volume)
    : domain_(domain), law_(law), nitsche_(nitsche) {
  const NodeSet& nodes = domain.nodes();
  for (const BoundaryCondition& bc : scene.boundary) {
    if (!bc.is_dirichlet() || bc.select.kind == Selection::Kind::point) continue;
    Constraint c;
    c.where = bc.where;
    std::vector<Index> facets = domain.facets_in(bc.select);
    c.points = domain.boundary_points(facets, facet_rule);
    c.shapes = domain.shapes_at(c.points.position, "the boundary quadrature point");
    const std::size_t per_facet = c.points.position.size() / facets.size();
    for (std::size_t q = 0; q < c.points.position.size(); ++q) {
      c.facet.push_back(facets[q / per_facet]);
      // The finest spacing among the point's nodes: on a graded lattice the
      // mean lets the coarse nodes weaken the term.
      double h = std::numeric_limits<double>::infinity();
      for (Index I : c.shapes.neighbours.of(static_cast<Index>(q))) h = std::min(h, nodes.spacing[I]);
      c.alpha.push_back(penalty_factor * law_.p_wave_modulus() / h);
    }
    for (int i = 0; i < domain.dimension(); ++i) {
      if (!bc.fixed[i] && !bc.displacement[i]) continue;
      c.projection(i, i) = 1.0;
      c.value[i] = bc.fixed[i] ? 0.0 : *bc.displacement[i];
    }
    constraints_.push_back(std::move(c));
  }
  safety_ = nitsche_safety(scene.discretization.meshless);
  if (nitsche_ && !constraints_.empty()) set_nitsche_alpha(volume);
}

namespace {

/// sigma(E) n for the small-strain isotropic law at rest, E a displacement gradient.
Vec3 traction(const Mat3& E, const Vec3& n, const Lame& lame) {
  const Mat3 strain = 0.5 * (E + E.transpose());
  return (lame.lambda * strain.trace() * Mat3::Identity() + 2.0 * lame.mu * strain) * n;
}


}  // namespace

void WeakBoundaryConditions::set_nitsche_alpha(const VolumePoints& volume) {
  const int dim = domain_.dimension();
  const Lame& lame = law_.lame();
  const Index N = domain_.nodes().size();
  std::vector<double> diagonal = material_diagonal(volume.table, volume.weight, lame, N);
  if (volume.ranks) volume.ranks->sum_on_every_rank(diagonal);
  // Per dof (k, i): sum over every constrained point of w_b |Pi sigma(e_i (x) g_k) n|^2.
  std::vector<double> pull(dim * N, 0.0);
  for (const Constraint& c : constraints_)
    for (Index q = 0; q < c.shapes.point_count(); ++q) {
      auto near = c.shapes.neighbours.of(q);
      for (std::size_t k = 0; k < near.size(); ++k)
        for (int i = 0; i < dim; ++i) {
          Mat3 E = Mat3::Zero();
          for (int l = 0; l < dim; ++l) E(i, l) = c.shapes.gradients_of(q)[dim * k + l];
          pull[dim * near[k] + i] +=
              c.points.weight[q] * (c.projection * traction(E, c.points.normal[q], lame)).squaredNorm();
        }
    }
  set_face_alpha(node_quotients(pull, diagonal));
  for (Constraint& c : constraints_) c.rest_alpha = c.alpha;
}

void WeakBoundaryConditions::refresh_alpha(const Vector& u, const VolumePoints& volume) {
  if (!nitsche_ || law_.is_linear() || constraints_.empty()) return;
  if (u.isZero(0.0)) {
    for (Constraint& c : constraints_) c.alpha = c.rest_alpha;
    return;
  }
  const int dim = domain_.dimension();
  const Index N = domain_.nodes().size();
  std::vector<double> diagonal = material_diagonal(volume.table, volume.weight, law_, u, N);
  if (volume.ranks) volume.ranks->sum_on_every_rank(diagonal);
  // As at rest, with the traction of e_i (x) g_k through the tangent at the point:
  // t_j = sum_lm dP_jl/dF_im g_m n_l.
  std::vector<double> pull(dim * N, 0.0);
  for (const Constraint& c : constraints_)
    for (Index q = 0; q < c.shapes.point_count(); ++q) {
      Mat3 P;
      Mat9 A;
      law_.stress_and_tangent(deformation_gradient(c.shapes, q, u), P, A);
      auto near = c.shapes.neighbours.of(q);
      const double* g = c.shapes.gradients_of(q);
      const Vec3& n = c.points.normal[q];
      for (std::size_t k = 0; k < near.size(); ++k)
        for (int i = 0; i < dim; ++i) {
          Vec3 t = Vec3::Zero();
          for (int j = 0; j < dim; ++j)
            for (int l = 0; l < dim; ++l)
              for (int m = 0; m < dim; ++m) t[j] += A(j + 3 * l, i + 3 * m) * g[dim * k + m] * n[l];
          pull[dim * near[k] + i] += c.points.weight[q] * (c.projection * t).squaredNorm();
        }
    }
  set_face_alpha(node_quotients(pull, diagonal));
  for (Constraint& c : constraints_)
    for (std::size_t q = 0; q < c.alpha.size(); ++q) {
      c.alpha[q] = std::max(c.alpha[q], c.rest_alpha[q]);
      if (c.rest_alpha[q] > 0.0) largest_growth_ = std::max(largest_growth_, c.alpha[q] / c.rest_alpha[q]);
    }
}

std::vector<double> WeakBoundaryConditions::node_quotients(const std::vector<double>& pull,
                                                           const std::vector<double>& diagonal) const {
  const int dim = domain_.dimension();
  const Index N = domain_.nodes().size();
  std::vector<double> quotient(N, 0.0);
  for (Index k = 0; k < N; ++k)
    for (int i = 0; i < dim; ++i)
      if (diagonal[dim * k + i] > 0.0) quotient[k] = std::max(quotient[k], pull[dim * k + i] / diagonal[dim * k + i]);
  return quotient;
}

void WeakBoundaryConditions::set_face_alpha(const std::vector<double>& quotient) {
  for (Constraint& c : constraints_) {
    // The points come face by face, the same number each: a face takes its nodes' largest.
    const Index count = c.shapes.point_count();
    Index per_face = 1;
    while (per_face < count && c.facet[per_face] == c.facet[0]) ++per_face;
    for (Index first = 0; first < count; first += per_face) {
      double largest = 0.0;
      for (Index q = first; q < first + per_face; ++q)
        for (Index k : c.shapes.neighbours.of(q)) largest = std::max(largest, quotient[k]);
      for (Index q = first; q < first + per_face; ++q) c.alpha[q] = safety_ * largest;
    }
  }
}

std::pair<Index, Index> WeakBoundaryConditions::own_points(const Constraint& c) const {
  return even_part(c.shapes.point_count(), share_.rank, share_.count);
}

void WeakBoundaryConditions::point_tangent(const Constraint& c, Index q, const Vector& u, std::vector<double>& block,
                                           std::vector<Mat3>& T) const {
  const int dim = domain_.dimension();
  auto near = c.shapes.neighbours.of(q);
  const Index n = static_cast<Index>(near.size()), size = n * dim;
  const double* phi = c.shapes.values_of(q);
  const double* g = c.shapes.gradients_of(q);
  const double w = c.points.weight[q], alpha = c.alpha[q];
  const Vec3& normal = c.points.normal[q];
  // The definite tangent keeps the penalty part alone: the consistency terms
  // are indefinite once the deformed material is stiffer than the alpha set
  // at rest (an EFG block swinging under gravity, Nitsche at the clamp).
  const bool consistency = nitsche_ && !law_.definite_tangent();
  if (consistency) {  // T_a(j, i) = (dP/dF : e_i (x) g_a) n, component j
    Mat3 P;
    Mat9 A;
    law_.stress_and_tangent(deformation_gradient(c.shapes, q, u), P, A);
    T.assign(n, Mat3::Zero());
    for (Index a = 0; a < n; ++a)
      for (int j = 0; j < dim; ++j)
        for (int i = 0; i < dim; ++i)
          for (int l = 0; l < dim; ++l)
            for (int m = 0; m < dim; ++m) T[a](j, i) += A(j + 3 * l, i + 3 * m) * g[dim * a + m] * normal[l];
  }
  for (Index a = 0; a < n; ++a)
    for (Index b = 0; b < n; ++b) {
      Mat3 K = alpha * phi[a] * phi[b] * c.projection;
      if (consistency) K -= phi[a] * (c.projection * T[b]) + phi[b] * (c.projection * T[a]).transpose();
      for (int i = 0; i < dim; ++i)
        for (int k = 0; k < dim; ++k) block[(dim * a + i) * size + dim * b + k] += w * K(i, k);
    }
}

double WeakBoundaryConditions::point_force(const Constraint& c, Index q, const Vector& u, double* force) const {
  const int dim = domain_.dimension();
  auto near = c.shapes.neighbours.of(q);
  const double* phi = c.shapes.values_of(q);
  const double* g = c.shapes.gradients_of(q);
  const double w = c.points.weight[q], alpha = c.alpha[q];
  const Vec3& normal = c.points.normal[q];
  const Vec3 d = c.projection * (interpolated_displacement(c.shapes, q, u) - c.value);
  double energy = 0.5 * w * alpha * d.squaredNorm();
  Vec3 Pn = Vec3::Zero();
  Mat3 W = Mat3::Zero();  // W(i, m) = d (d . P n) / dF(i, m): the adjoint term once for all neighbours
  if (nitsche_) {
    const Mat3 F = deformation_gradient(c.shapes, q, u);
    const Mat3 P = law_.stress(F);
    Pn = c.projection * (P * normal);
    energy -= w * d.dot(P * normal);
    // dP/dF has major symmetry (every law derives from an energy), so W is
    // P's derivative along d (x) n: exact from two stresses for a linear law,
    // a central difference (relative error ~1e-10) otherwise.
    const Mat3 D = d * normal.transpose();
    const double size = D.norm();
    if (size > 0.0) {
      if (law_.is_linear()) {
        W = law_.stress(Mat3::Identity() + D) - law_.stress(Mat3::Identity());
      } else {
        const double h = 1e-5;
        W = (size / (2.0 * h)) * (law_.stress(F + (h / size) * D) - law_.stress(F - (h / size) * D));
      }
    }
  }
  for (std::size_t a = 0; a < near.size(); ++a)
    for (int i = 0; i < dim; ++i) {
      double r = alpha * phi[a] * d[i];
      if (nitsche_) {
        r -= phi[a] * Pn[i];
        for (int m = 0; m < dim; ++m) r -= W(i, m) * g[dim * a + m];
      }
      force[dim * a + i] = w * r;
    }
  return energy;
}

double WeakBoundaryConditions::terms(const Vector& u, Vector* f) const {
  const int dim = domain_.dimension();
  double energy = 0.0;
  for (const Constraint& c : constraints_) {
    const auto [begin, end] = own_points(c);
    if (begin == end) continue;
    const Index* start = c.shapes.neighbours.start.data();
    forces_.resize(static_cast<std::size_t>(dim) * (start[end] - start[begin]));  // not in the region: may throw
    ParallelFailure failure;
#pragma omp parallel for schedule(static) reduction(+ : energy)
    for (Index q = begin; q < end; ++q)
      failure.run([&] { energy += point_force(c, q, u, forces_.data() + dim * (start[q] - start[begin])); });
    failure.rethrow_if_failed();
    if (!f) continue;
    // Each point's part into f, in order (no two threads write one entry).
    for (Index q = begin; q < end; ++q) {
      auto near = c.shapes.neighbours.of(q);
      const double* part = forces_.data() + dim * (start[q] - start[begin]);
      for (std::size_t a = 0; a < near.size(); ++a)
        for (int i = 0; i < dim; ++i) (*f)[dim * near[a] + i] += part[dim * a + i];
    }
  }
  return energy;
}

void WeakBoundaryConditions::add_tangent(const Vector& u, const BlockSink& sink) const {
  std::vector<double> block;
  std::vector<Index> dofs;
  std::vector<Mat3> scratch;
  for (const Constraint& c : constraints_) {
    const auto [begin, end] = own_points(c);
    for (Index q = begin; q < end; ++q) {
      neighbour_dofs(c.shapes, q, dofs);
      block.assign(dofs.size() * dofs.size(), 0.0);
      point_tangent(c, q, u, block, scratch);
      sink(dofs, block);
    }
  }
}

void WeakBoundaryConditions::visit_couplings(const CouplingVisitor& visit) const {
  std::vector<Index> dofs;
  for (const Constraint& c : constraints_)
    for (Index q = 0; q < c.shapes.point_count(); ++q) {
      neighbour_dofs(c.shapes, q, dofs);
      visit(dofs);
    }
}

void WeakBoundaryConditions::mark_reached(std::vector<char>& reached) const {
  for (const Constraint& c : constraints_) {
    const auto [begin, end] = own_points(c);
    for (Index q = begin; q < end; ++q)
      for (Index J : c.shapes.neighbours.of(q)) reached[J] = 1;
  }
}

Vec3 WeakBoundaryConditions::reaction(const Vector& u, const Selection& selection) const {
  std::vector<Index> facets = domain_.facets_in(selection, false);
  std::vector<char> inside(domain_.facets().count(), 0);
  for (Index f : facets) inside[f] = 1;
  Vec3 total = Vec3::Zero();
  for (const Constraint& c : constraints_)
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

void WeakBoundaryConditions::update_for_cuts(const MeshlessDomain& domain, std::span<const char> changed,
                                             const VolumePoints& volume) {
  for (Constraint& c : constraints_) {
    std::vector<Index> held;
    for (Index q = 0; q < c.shapes.point_count(); ++q) {
      auto near = c.shapes.neighbours.of(q);
      if (std::any_of(near.begin(), near.end(), [&](Index J) { return changed[J]; })) held.push_back(q);
    }
    domain.refresh_rows(c.shapes, c.points.position, held, "the boundary quadrature point");
  }
  if (nitsche_ && !constraints_.empty()) set_nitsche_alpha(volume);
}

std::string WeakBoundaryConditions::describe_node(Index node) const {
  std::ostringstream out;
  for (const Constraint& c : constraints_) {
    Index reaching = 0;
    double low = std::numeric_limits<double>::infinity(), high = 0.0;
    for (Index q = 0; q < c.shapes.point_count(); ++q) {
      auto near = c.shapes.neighbours.of(q);
      if (std::find(near.begin(), near.end(), node) == near.end()) continue;
      ++reaching;
      low = std::min(low, c.alpha[q]), high = std::max(high, c.alpha[q]);
    }
    if (reaching == 0) continue;
    out << "; its support reaches " << reaching << " boundary points of " << c.where.describe() << ", imposed by "
        << (nitsche_ ? "Nitsche" : "penalty") << " with alpha " << low << " to " << high << " Pa/m";
    if (nitsche_)
      out << " (too small an alpha makes Nitsche's form indefinite: raise discretization.meshless.nitsche_safety, "
             "or use essential: penalty)";
  }
  return out.str();
}

double WeakBoundaryConditions::smallest_alpha() const {
  double a = std::numeric_limits<double>::infinity();
  for (const Constraint& c : constraints_)
    for (double v : c.alpha) a = std::min(a, v);
  return a;
}

double WeakBoundaryConditions::largest_alpha() const {
  double a = 0.0;
  for (const Constraint& c : constraints_)
    for (double v : c.alpha) a = std::max(a, v);
  return a;
}

}  // namespace kerf
