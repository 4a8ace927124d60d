#pragma once
// What a solver needs of a discretized body, whatever the method (fem, efg,
// nodal). Degrees of freedom are node-major: dof = dofs_per_node * node + component.
// Units: displacement m, force N, mass kg, time s.
#include <array>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/types.h"
#include "problem/scene.h"

namespace kerf {

/// Receives one dense block of a global matrix: `values` is n x n row-major for
/// n = dofs.size(). May be called from several threads at once, but two calls
/// running at the same time never share a dof (bodies colour their blocks), so
/// a sink may add without atomics.
using BlockSink = std::function<void(std::span<const Index> dofs, std::span<const double> values)>;

/// Called once per block that assembly will ever write: the sparsity pattern.
using CouplingVisitor = std::function<void(std::span<const Index> dofs)>;

struct DirichletDof {
  Index dof;
  double value;  // m
  /// A static run's load steps scale the value; false when the value already
  /// is the one at this load (a force-driven sphere's position).
  bool scales_with_load = true;
};

/// The displacement at a point as weights on nodal values: u(x) = sum_k w_k u_{node_k}.
struct PointInterpolation {
  std::vector<Index> nodes;
  std::vector<double> weights;
};

/// A field written to ParaView: per point or per cell, `components` values each.
struct OutputField {
  std::string name;
  int components = 1;
  std::vector<double> values;
};

/// The body as ParaView sees it at one instant: reference points, cells with
/// VTK cell types, and fields. Points are always 3D (z = 0 in 2D).
struct BodySnapshot {
  std::vector<Vec3> points;
  std::vector<Index> connectivity;
  std::vector<Index> offsets;          // end of each cell in connectivity
  std::vector<std::uint8_t> cell_types;  // VTK cell type ids
  std::vector<OutputField> point_fields;
  std::vector<OutputField> cell_fields;
};

/// A scalar field on a lattice (an Enrichment Grid's phi), for a .vti file.
struct LatticeSnapshot {
  std::string name;
  Vec3 origin = Vec3::Zero();  // m
  std::array<Vec3, 3> axes{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};  // unit, world frame
  std::array<Index, 3> count{1, 1, 1};
  double spacing = 1.0;        // m
  std::vector<double> values;  // axis 0 fastest
};

/// A quadrature point on the boundary, for surface terms that follow the
/// deformation (contact): u(position) = interpolation applied to the nodal values.
struct SurfacePoint {
  Vec3 position = Vec3::Zero();  // reference (m)
  double weight = 0.0;           // m^2 (2D: m, per metre of thickness)
  double size = 0.0;             // the facet's edge length (m): the local resolution
  PointInterpolation interpolation;
};

/// Boundary quadrature points and the straight facets they lie on (triangles;
/// in 2D segments with c == b), in the reference configuration.
struct SurfaceSamples {
  std::vector<SurfacePoint> points;
  std::vector<std::array<Vec3, 3>> facets;
};

/// Where a rigid indenter stands (DiscreteBody::contact_reading).
struct ContactReading {
  double indentation = 0.0;      // depth of the sphere below the undeformed surface (m)
  Vec3 force = Vec3::Zero();     // force the sphere exerts on the body (N)
  Vec3 displacement = Vec3::Zero();  // of the sphere's centre (m)
};

/// What a growing cut changed in a body.
struct CutUpdate {
  Index nodes = 0;   // nodes whose enriched weight changed
  Index points = 0;  // integration points whose shape functions were recomputed
};

class DiscreteBody {
 public:
  virtual ~DiscreteBody() = default;

  virtual int dofs_per_node() const = 0;
  virtual Index node_count() const = 0;
  /// Reference position of a node (m); z = 0 in 2D.
  virtual Vec3 node_position(Index node) const = 0;
  Index dof_count() const { return dofs_per_node() * node_count(); }

  virtual void visit_couplings(const CouplingVisitor& visit) const = 0;
  /// f_int(u) (N), dof_count entries.
  virtual void internal_force(const Vector& u, Vector& f) const = 0;
  /// K(u) = d f_int / du into `sink`; also f_int(u) into *f when f is given.
  virtual void tangent(const Vector& u, const BlockSink& sink, Vector* f) const = 0;
  virtual double strain_energy(const Vector& u) const = 0;
  /// True when f_int is linear in u: the stiffness never changes.
  virtual bool is_linear() const = 0;

  /// Diagonal mass (kg per dof).
  virtual Vector lumped_mass() const = 0;
  virtual void consistent_mass(const BlockSink& sink) const = 0;

  /// f_ext(t) (N): body forces and boundary loads.
  virtual void external_force(double t, Vector& f) const = 0;
  /// The constrained dofs and their prescribed values at time t, sorted by dof.
  virtual std::vector<DirichletDof> dirichlet(double t) const = 0;

  /// A cheap safe central-difference step with the lumped mass (s), from
  /// element frequency bounds at the undeformed state; nullopt when the method
  /// has no bound cheaper than the assembled stiffness (meshless: every bound
  /// needs all the point blocks), and the stepper's Lanczos bound is used alone.
  virtual std::optional<double> critical_time_step() const = 0;

  /// The nodes a selection takes; throws (naming the scene line) when it takes none.
  virtual std::vector<Index> select_nodes(const Selection& selection) const = 0;
  /// How to evaluate u at x, or nullopt when x lies outside the body.
  virtual std::optional<PointInterpolation> interpolation_at(const Vec3& x) const = 0;
  virtual void snapshot(const Vector& u, BodySnapshot& out) const = 0;

  /// Counts for the summary: cells (FEM) or integration points (meshless).
  virtual Index element_count() const = 0;
  /// Mean number of other nodes a node is coupled to (FEM: through cells) or
  /// whose support covers it (meshless).
  virtual double mean_neighbors() const = 0;

  /// Brings the body's cuts to time t: where a new piece appeared, the shape
  /// functions it affects are rebuilt (the dofs stay the same, so the state
  /// carries over). nullopt when nothing changed.
  virtual std::optional<CutUpdate> advance_cuts(double t) {
    (void)t;
    return std::nullopt;
  }

  /// The cuts as they stand, for ParaView: their pieces (lines in 2D,
  /// triangles in 3D) in the reference configuration, with the opening
  /// u(x + delta n) - u(x - delta n) across the cut at each vertex. Empty
  /// without cuts.
  virtual void cut_snapshot(const Vector& u, BodySnapshot& out) const {
    (void)u;
    out = BodySnapshot{};
  }
  /// The Enrichment Grids' phi, one per grid-enriched cut present.
  virtual std::vector<LatticeSnapshot> enrichment_lattices() const { return {}; }

  /// Quadrature points on the boundary facets that have a corner inside
  /// `region` (`points_per_direction` Gauss points per facet direction).
  virtual SurfaceSamples surface_samples(const Box& region, int points_per_direction) const = 0;

  /// A body made of a linear elastic body and terms that are not linear
  /// (contact) returns the linear body here, whose dofs are the first of this
  /// body's: implicit solvers assemble its stiffness once. Null otherwise.
  virtual const DiscreteBody* linear_part() const { return nullptr; }
  /// The forces of what linear_part() leaves out, added into f (N), and their
  /// tangent into *sink when given.
  virtual void add_nonlinear_part(const Vector& u, Vector& f, const BlockSink* sink) const {
    (void)u, (void)f, (void)sink;
  }
  /// Augmented Lagrangian update of constraint multipliers (contact) at a
  /// converged static u under load factor t, with the prescribed positions
  /// that depend on the solution (a force-driven sphere's); true when a
  /// constraint is still violated beyond its tolerance, so the static solve
  /// is repeated with the new multipliers and dirichlet(t).
  virtual bool augment(const Vector& u, double t) {
    (void)u, (void)t;
    return false;
  }
  /// The state of the scene's indenter `index` at u; nullopt without contact.
  virtual std::optional<ContactReading> contact_reading(int index, const Vector& u) const {
    (void)index, (void)u;
    return std::nullopt;
  }

  /// Figures of the discretization as it stands, into the summary's
  /// `solver` counters (meshless: the moment matrices' condition numbers).
  virtual void add_diagnostics(std::map<std::string, double>& counters) const { (void)counters; }

  /// The total force (N) that constraints imposed weakly (EFG penalty or
  /// Nitsche) on the boundary faces inside `selection` exert on the body at
  /// displacement u. Zero for strong constraints, whose reactions are read
  /// from the constrained dofs.
  virtual Vec3 weak_reaction(const Vector& u, const Selection& selection) const {
    (void)u, (void)selection;
    return Vec3::Zero();
  }
};

}  // namespace kerf
