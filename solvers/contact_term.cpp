#include "solvers/contact_term.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/check.h"
#include "geometry/facet_distance.h"

namespace kerf {
namespace {

constexpr double implicit_penalty_factor = 100.0;   // k_q = factor E* / size
constexpr double explicit_penalty_factor = 10.0;    // k_q = factor E* / size
// A point may penetrate 1e-4 of its facet's size, or 1e-3 of the sphere's
// travel: a flat facet cannot touch the sphere at all its Gauss points, so the
// first alone can take many rounds of bending the facets; the second bounds
// the error the penetration adds to the indentation.
constexpr double penetration_per_size = 1.0e-4;
constexpr double penetration_per_travel = 1.0e-3;
constexpr double force_tolerance = 1.0e-4;  // relative, force-driven spheres
constexpr int contact_points_per_direction = 2;

/// Distance (m) from x to the segment [a, b].
double distance_to_segment(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((x - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (x - (a + t * ab)).norm();
}

/// How deep a sphere pressed with `force` (N; 2D: N/m) sinks into a half-space
/// of modulus e_star (Hertz): the scale of its travel when force-driven (m).
double hertz_depth(int dim, double force, double radius, double e_star) {
  if (dim == 3) return std::pow(3.0 * force / (4.0 * e_star * std::sqrt(radius)), 2.0 / 3.0);
  const double half_width2 = 4.0 * radius * force / (std::numbers::pi * e_star);  // cylinder: b^2
  return half_width2 / radius;
}

}  // namespace

ContactTerm::ContactTerm(const Scene& scene, const SurfaceSampling& surface, Index first_dof, int dofs_per_node,
                         RankShare ranks)
    : first_dof_(first_dof), dim_(dofs_per_node), ranks_(ranks) {
  static_ = scene.solve.analysis == Analysis::static_analysis;
  explicit_ = !scene.solve.solves_linear_systems();
  for (const ContactSphere& c : scene.contact) spheres_.push_back(place(c, surface, scene.material, scene.solve.dt));
}

ContactTerm::Sphere ContactTerm::place(const ContactSphere& c, const SurfaceSampling& surface,
                                       const Material& material, double dt) const {
  const double e_star = material.young / (1.0 - material.poisson * material.poisson);
  Sphere s;
  s.center = c.center;
  s.radius = c.radius;
  s.force = c.force;
  s.displacement = c.displacement;
  const double r = c.radius;
  // The boundary the sphere can reach: within its radius of its path plus a
  // margin of twice the travel (the path: the prescribed displacement, or
  // three Hertz depths of its force on a half-space of this material).
  Vec3 travel;
  if (c.force) {
    s.direction = c.force->normalized();  // nonzero, and in dynamic runs along an axis (validate())
    s.half_space_depth = hertz_depth(dim_, c.force->norm(), r, e_star);
    travel = 3.0 * s.half_space_depth * s.direction;
  } else {
    travel = *c.displacement;
  }
  s.travel = travel;
  s.largest_force = c.force ? c.force->norm() : 0.0;
  s.where = c.where.describe();
  const double reach = r + 2.0 * travel.norm();
  Box region;
  region.min = c.center.cwiseMin(c.center + travel) - Vec3::Constant(reach);
  region.max = c.center.cwiseMax(c.center + travel) + Vec3::Constant(reach);
  SurfaceSamples samples = surface.surface_samples(region, contact_points_per_direction);
  s.facets = std::move(samples.facets);
  for (SurfacePoint& p : samples.points)
    if (distance_to_segment(p.position, c.center, c.center + travel) < reach + p.size) s.points.push_back(std::move(p));
  KERF_CHECK(!s.points.empty(), c.where.describe(), ": key 'sphere': the sphere (centre [", c.center.transpose(),
             "], radius ", r, " m) cannot reach the body's boundary along its motion; expected a sphere on or "
             "near the surface, moving into it");
  const double overlap = r - distance_to_facets(c.center, s.facets);
  KERF_CHECK(overlap <= 1e-6 * r, c.where.describe(), ": key 'sphere': the sphere starts ", overlap,
             " m inside the body; expected it to start on or above the surface (move the centre out by that much)");
  const double volume = dim_ == 3 ? 4.0 / 3.0 * std::numbers::pi * r * r * r : std::numbers::pi * r * r;
  s.mass = material.density * volume;
  double total_penalty = 0.0;  // N/m, every point pressing at once
  for (const SurfacePoint& p : s.points) {
    s.penalty.push_back((explicit_ ? explicit_penalty_factor : implicit_penalty_factor) * e_star / p.size);
    total_penalty += s.penalty.back() * p.weight;
  }
  s.multiplier.assign(s.points.size(), 0.0);
  // An explicit force-driven sphere is scaled up in mass, if need be, so that
  // its contact springs do not shorten the critical step (omega dt <= 1).
  if (explicit_ && s.force) s.mass = std::max(s.mass, total_penalty * dt * dt);
  return s;
}

void ContactTerm::move_sphere(Index sphere, const Vec3& displacement) {
  Sphere& s = spheres_.at(static_cast<std::size_t>(sphere));
  KERF_CHECK(s.displacement, s.where, ": key 'force': contact ", sphere, " is driven by a force: push it with a force ",
             "(push_sphere), or give it a displacement in the scene to move it");
  const double off = distance_to_segment(s.center + displacement, s.center, s.center + s.travel);
  KERF_CHECK(off <= 2.0 * s.travel.norm() * (1.0 + 1e-12), s.where, ": key 'displacement': moving the sphere by [",
             displacement.transpose(), "] m takes it ", off, " m from its scene path (the centre to [",
             (s.center + s.travel).transpose(), "]), past the ", 2.0 * s.travel.norm(), " m around it whose surface ",
             "was sampled for it; expected a move within that, or a scene displacement reaching as far");
  s.displacement = displacement;
}

void ContactTerm::push_sphere(Index sphere, const Vec3& force) {
  Sphere& s = spheres_.at(static_cast<std::size_t>(sphere));
  KERF_CHECK(s.force, s.where, ": key 'displacement': contact ", sphere, " is driven by a displacement: move it ",
             "(move_sphere), or give it a force in the scene to push it");
  const bool on_line = force.cross(s.direction).norm() <= 1e-12 * std::max(force.norm(), 1e-300);
  KERF_CHECK(on_line && force.norm() <= s.largest_force * (1.0 + 1e-12), s.where, ": key 'force': pushing with [",
             force.transpose(), "] N leaves the sphere's scene force line or exceeds it (", s.largest_force,
             " N along [", s.direction.transpose(), "], which set the surface sampled for it); expected a force ",
             "along that line, no larger");
  s.force = force;
}

void ContactTerm::refresh_interpolations(const DiscreteBody& body, std::span<const Index> changed_nodes) {
  std::vector<char> changed(body.node_count(), 0);
  for (Index I : changed_nodes) changed[I] = 1;
  for (Sphere& s : spheres_)
    for (SurfacePoint& p : s.points) {
      if (std::none_of(p.interpolation.nodes.begin(), p.interpolation.nodes.end(), [&](Index I) { return changed[I]; }))
        continue;
      std::optional<PointInterpolation> now = body.interpolation_at(p.position);
      KERF_CHECK(now && now->nodes == p.interpolation.nodes, "internal: the contact point [", p.position.transpose(),
                 "] is no longer covered by the nodes it was (a cut may only change weights in place)");
      p.interpolation = std::move(*now);
    }
}

Vec3 ContactTerm::sphere_displacement(std::size_t i, const Vector& u) const {
  Vec3 d = Vec3::Zero();
  for (int k = 0; k < dim_; ++k) d[k] = u[sphere_dof(i) + k];
  return d;
}

ContactTerm::PointContact ContactTerm::evaluate(const Sphere& s, std::size_t q, const Vec3& centre,
                                                const Vector& u) const {
  const SurfacePoint& p = s.points[q];
  const Vec3 x = p.position + interpolate(p.interpolation, u, dim_);
  PointContact c;
  const Vec3 d = x - centre;
  c.distance = d.norm();
  c.penetration = s.radius - c.distance;
  c.traction = s.multiplier[q] + s.penalty[q] * c.penetration;
  c.active = c.traction > 0.0 && c.distance > 0.0;
  if (c.active) c.normal = d / c.distance;
  return c;
}

void ContactTerm::visit_couplings(const CouplingVisitor& visit) const {
  std::vector<Index> dofs;
  for (std::size_t i = 0; i < spheres_.size(); ++i)
    for (const SurfacePoint& p : spheres_[i].points) {
      dofs.clear();
      for (Index n : p.interpolation.nodes)
        for (int k = 0; k < dim_; ++k) dofs.push_back(dim_ * n + k);
      for (int k = 0; k < dim_; ++k) dofs.push_back(sphere_dof(i) + k);
      visit(dofs);
    }
}

std::vector<Index> ContactTerm::own_point_nodes() const {
  std::vector<Index> nodes;
  for (const Sphere& s : spheres_) {
    const auto [begin, end] = own_points(s);
    for (std::size_t q = begin; q < end; ++q)
      nodes.insert(nodes.end(), s.points[q].interpolation.nodes.begin(), s.points[q].interpolation.nodes.end());
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

void ContactTerm::add(const Vector& u, Vector& f, const BlockSink* sink) const {
  std::vector<Index>& dofs = dofs_;
  std::vector<double>& beta = beta_;
  std::vector<double>& block = block_;
  for (std::size_t i = 0; i < spheres_.size(); ++i) {
    const Sphere& s = spheres_[i];
    const Vec3 centre = s.center + sphere_displacement(i, u);
    const auto [first, end] = own_points(s);
    for (std::size_t q = first; q < end; ++q) {
      const PointContact c = evaluate(s, q, centre, u);
      if (!c.active) continue;
      const SurfacePoint& p = s.points[q];
      // x - c = sum_k N_k u_k - u_sphere + const: coefficients beta on the nodes' and the sphere's dofs.
      const std::size_t m = p.interpolation.nodes.size();
      dofs.clear();
      beta.assign(p.interpolation.weights.begin(), p.interpolation.weights.end());
      beta.push_back(-1.0);
      for (Index n : p.interpolation.nodes)
        for (int k = 0; k < dim_; ++k) dofs.push_back(dim_ * n + k);
      for (int k = 0; k < dim_; ++k) dofs.push_back(sphere_dof(i) + k);
      // Energy w / (2 k) <lambda + k (R - |x - c|)>^2: force -w t dN, ...
      const Vec3 force = -p.weight * c.traction * c.normal;
      for (std::size_t a = 0; a <= m; ++a)
        for (int k = 0; k < dim_; ++k) f[dofs[dim_ * a + k]] += beta[a] * force[k];
      if (!sink) continue;
      // ... and its Hessian in x - c, normal part w k n n^T. The curvature part
      // -w t (I - n n^T) / |x - c| is left out: while the first iterations
      // overshoot (t orders of magnitude too large) it makes the matrix
      // indefinite, and at convergence it is penetration / R ~ 1e-4 of the rest.
      const Mat3 H = p.weight * s.penalty[q] * c.normal * c.normal.transpose();
      const std::size_t n = dofs.size();
      block.assign(n * n, 0.0);
      for (std::size_t a = 0; a <= m; ++a)
        for (std::size_t b = 0; b <= m; ++b)
          for (int k = 0; k < dim_; ++k)
            for (int l = 0; l < dim_; ++l) block[(dim_ * a + k) * n + dim_ * b + l] = beta[a] * beta[b] * H(k, l);
      (*sink)(dofs, block);
    }
  }
}

ContactTerm::AugmentationState ContactTerm::augmentation_state() const {
  AugmentationState state;
  for (const Sphere& s : spheres_) {
    state.multipliers.push_back(s.multiplier);
    state.depths.push_back({s.depth, s.previous_depth, s.previous_g});
  }
  return state;
}

void ContactTerm::restore(const AugmentationState& state) {
  for (std::size_t i = 0; i < spheres_.size(); ++i) {
    Sphere& s = spheres_[i];
    s.multiplier = state.multipliers[i];
    s.depth = state.depths[i][0];
    s.previous_depth = state.depths[i][1];
    s.previous_g = state.depths[i][2];
  }
}

bool ContactTerm::augment(const Vector& u, double load) {
  // Multipliers change only when another solve follows, so that a settled
  // state keeps the tractions it is in equilibrium with.
  KERF_CHECK(static_, "internal: contact multipliers are updated in static runs only");
  bool violated = false;
  std::vector<std::vector<double>> multipliers(spheres_.size());
  for (std::size_t i = 0; i < spheres_.size(); ++i) {
    Sphere& s = spheres_[i];
    const Vec3 travel = sphere_displacement(i, u);
    const Vec3 centre = s.center + travel;
    double push = 0.0;  // N: the force along the sphere's direction
    bool penetrates = false;
    multipliers[i] = s.multiplier;  // another rank's points keep theirs (unused here)
    const auto [first, end] = own_points(s);
    for (std::size_t q = first; q < end; ++q) {
      const PointContact c = evaluate(s, q, centre, u);
      multipliers[i][q] = std::max(0.0, c.traction);
      if (c.active) push += s.points[q].weight * c.traction * c.normal.dot(s.direction);
      if (c.penetration > std::max(penetration_per_size * s.points[q].size, penetration_per_travel * travel.norm()))
        penetrates = true;
    }
    push = total(push);
    if (total(penetrates ? 1.0 : 0.0) > 0.0) violated = true;
    if (!s.force) continue;
    const double target = load * s.force->norm();
    if (std::abs(push - target) <= force_tolerance * target) continue;
    violated = true;
    step_depth(s, push, target, load);
  }
  if (violated)
    for (std::size_t i = 0; i < spheres_.size(); ++i) spheres_[i].multiplier = std::move(multipliers[i]);
  return violated;
}

void ContactTerm::step_depth(Sphere& s, double push, double target, double load) const {
  // Secant on g = F^(2/3), linear in the depth for Hertz; until the sphere
  // presses, steps of its half-space depth.
  const double g = std::pow(push, 2.0 / 3.0), g_target = std::pow(target, 2.0 / 3.0);
  double next;
  if (push <= 0.0)
    next = s.depth + s.half_space_depth * std::max(load, 0.1);
  else if (s.previous_g <= 0.0 || g == s.previous_g)
    next = s.depth + (g_target - g) * s.half_space_depth / g_target;
  else
    next = s.depth + (g_target - g) * (s.depth - s.previous_depth) / (g - s.previous_g);
  s.previous_depth = s.depth;
  s.previous_g = g;
  s.depth = next;
}

ContactReading ContactTerm::reading(Index sphere, const Vector& u) const {
  const Sphere& s = spheres_[sphere];
  ContactReading reading;
  reading.displacement = sphere_displacement(sphere, u);
  const Vec3 centre = s.center + reading.displacement;
  reading.indentation = s.radius - distance_to_facets(centre, s.facets);
  const auto [first, end] = own_points(s);
  for (std::size_t q = first; q < end; ++q) {
    const PointContact c = evaluate(s, q, centre, u);
    if (c.active) reading.force += s.points[q].weight * c.traction * c.normal;
  }
  for (int k = 0; k < 3; ++k) reading.force[k] = total(reading.force[k]);
  return reading;
}

void ContactTerm::fill_lumped_mass(Vector& lumped) const {
  for (std::size_t i = 0; i < spheres_.size(); ++i) lumped.segment(sphere_dof(i), dim_).setConstant(spheres_[i].mass);
}

void ContactTerm::consistent_mass(const BlockSink& sink) const {
  if (ranks_.rank + 1 != ranks_.count) return;  // the sphere's rows are the last rank's: its mass once
  std::vector<Index> dofs(dim_);
  std::vector<double> block(dim_ * dim_);
  for (std::size_t i = 0; i < spheres_.size(); ++i) {
    std::fill(block.begin(), block.end(), 0.0);
    for (int k = 0; k < dim_; ++k) {
      dofs[k] = sphere_dof(i) + k;
      block[k * dim_ + k] = spheres_[i].mass;
    }
    sink(dofs, block);
  }
}

void ContactTerm::fill_external_force(Vector& f) const {
  for (std::size_t i = 0; i < spheres_.size(); ++i)
    if (spheres_[i].force) f.segment(sphere_dof(i), dim_) = spheres_[i].force->head(dim_);
}

void ContactTerm::append_dirichlet(std::vector<DirichletDof>& out) const {
  for (std::size_t i = 0; i < spheres_.size(); ++i) {
    const Sphere& s = spheres_[i];
    for (int k = 0; k < dim_; ++k) {
      const Index dof = sphere_dof(i) + k;
      if (s.displacement)
        out.push_back({dof, (*s.displacement)[k]});
      else if (static_)
        out.push_back({dof, s.depth * s.direction[k], false});
      else if (s.direction[k] == 0.0)
        out.push_back({dof, 0.0});  // dynamic: held across its force
    }
  }
}

}  // namespace kerf
