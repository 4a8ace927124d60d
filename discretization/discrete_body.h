#pragma once
// What every solver needs of a discretized body, whatever the method (fem,
// efg, nodal), and nothing more: the dofs, the couplings, internal force and
// tangent, mass, loads, constraints, the displacement at a point, a snapshot.
// What only some bodies offer (cuts in the shape functions, surface samples
// for contact, weak constraints, diagnostics, an element step bound) are the
// capabilities of discretization/body_capabilities.h, asked for once.
// Degrees of freedom are node-major: dof = dofs_per_node * node + component.
// Units: displacement m, force N, mass kg, time s.
//
// A distributed run will give a body the rows it owns; internal_force,
// tangent and the masses are the calls that will then assemble only those.
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/types.h"
#include "discretization/body_snapshot.h"
#include "problem/selection.h"

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

/// sum_k w_k u_{node_k} for a node-major u with `dim` components a node (z = 0 in 2D).
inline Vec3 interpolate(const PointInterpolation& p, const Vector& u, int dim) {
  Vec3 x = Vec3::Zero();
  for (std::size_t k = 0; k < p.nodes.size(); ++k)
    for (int i = 0; i < dim; ++i) x[i] += p.weights[k] * u[dim * p.nodes[k] + i];
  return x;
}

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
  /// Whether tangent() assembles the definite tangent (each point's dP/dF with
  /// its negative eigenvalues set to zero) instead of the exact one; the
  /// solver chooses (solve.tangent), the forces are the same either way.
  virtual void use_definite_tangent(bool definite) = 0;
  /// True when f_int is linear in u: the stiffness never changes.
  virtual bool is_linear() const = 0;
  /// An implicit time step (or substep) starts from u: a body whose terms are
  /// set from the state reached does it here (EFG's and nodal integration's
  /// Nitsche alpha); within the step the energy stays fixed. Static load
  /// steps do not call it, so a static answer does not depend on the
  /// increments taken (with it, EFG's soft block at 5 mm moved 2.7e-3
  /// between one increment and eight).
  virtual void begin_time_step(const Vector& /*u*/) {}
  /// False when the forces are tested with other functions than the
  /// displacement is made of (a Petrov-Galerkin body, as nodal integration
  /// with VCI): K is then not symmetric, and f_int is not the gradient of
  /// strain_energy.
  virtual bool symmetric_tangent() const { return true; }
  /// K(u) with the test functions equal to the trial ones (symmetric, and
  /// positive definite where the body is held): what a solver factorizes to
  /// precondition an unsymmetric tangent. The tangent itself for a Galerkin body.
  virtual void galerkin_tangent(const Vector& u, const BlockSink& sink) const { tangent(u, sink, nullptr); }

  /// Diagonal mass (kg per dof).
  virtual Vector lumped_mass() const = 0;
  virtual void consistent_mass(const BlockSink& sink) const = 0;

  /// f_ext(t) (N): body forces and boundary loads.
  virtual void external_force(double t, Vector& f) const = 0;
  /// The constrained dofs and their prescribed values at time t, sorted by dof.
  virtual std::vector<DirichletDof> dirichlet(double t) const = 0;

  /// The nodes a selection takes; throws (naming the scene line) when it takes none.
  virtual std::vector<Index> select_nodes(const Selection& selection) const = 0;
  /// How to evaluate u at x, or nullopt when x lies outside the body.
  virtual std::optional<PointInterpolation> interpolation_at(const Vec3& x) const = 0;
  virtual void snapshot(const Vector& u, BodySnapshot& out) const = 0;

  /// What is known of one dof, for a failed solve's message: the node, where
  /// it lies, its component, and what acts on it.
  virtual std::string describe_dof(Index dof) const;

  /// Counts for the summary: cells (FEM) or integration points (meshless).
  virtual Index element_count() const = 0;
  /// Mean number of other nodes a node is coupled to (FEM: through cells) or
  /// whose support covers it (meshless).
  virtual double mean_neighbors() const = 0;
};

}  // namespace kerf
