#pragma once
// What only some bodies offer, beside the core of discrete_body.h: each an
// interface of its own that a body implements when it has the feature, and
// that the factory, the run loop or a solver term asks for once with
// capability<C>(body) (null when the body has none).
//
//   SurfaceSampling        fem, efg, nodal   boundary quadrature points (contact)
//   WeakConstraints        efg               reactions of weakly imposed constraints
//   CutsInShapeFunctions   nodal, efg        a cut's new piece updates rows in place
//   CutsBySplitting        fem               a cut's new piece splits the cells it separates
//   EnrichmentLattices     efg, nodal        the Enrichment Grids' phi for ParaView
//   DiscretizationFigures  efg, nodal        MLS conditioning for the summary
//   ElementStepBound       fem               a cheap safe explicit step
//   MeshedBody             fem               the mesh a state is carried onto
//   MatrixAssembly         fem, efg          K written straight into a CSR matrix
//   PartitionedAssembly    fem               under MPI, only this rank's cells
#include <map>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "discretization/discrete_body.h"
#include "geometry/cut_surface.h"
#include "geometry/mesh.h"

namespace kerf {

struct Scene;

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

class SurfaceSampling {
 public:
  virtual ~SurfaceSampling() = default;
  /// Quadrature points on the boundary facets that have a corner inside
  /// `region` (`points_per_direction` Gauss points per facet direction).
  virtual SurfaceSamples surface_samples(const Box& region, int points_per_direction) const = 0;
};

class WeakConstraints {
 public:
  virtual ~WeakConstraints() = default;
  /// The total force (N) that the constraints imposed weakly (penalty or
  /// Nitsche) on the boundary faces inside `selection` exert on the body at u.
  virtual Vec3 weak_reaction(const Vector& u, const Selection& selection) const = 0;
};

/// What a growing cut changed in a body.
struct CutUpdate {
  Index nodes = 0;   // nodes whose enriched weight changed
  std::vector<Index> changed_nodes;  // those nodes: a point whose support holds none keeps its shape functions
  Index points = 0;  // integration points whose shape functions were recomputed
};

class CutsInShapeFunctions {
 public:
  virtual ~CutsInShapeFunctions() = default;
  /// Brings the body's cuts to time t: the shape functions the new pieces
  /// affect are rebuilt in place (the dofs and the sparsity stay, so the state
  /// carries over unchanged).
  virtual CutUpdate update_for_cuts(double t) = 0;
};

class CutsBySplitting {
 public:
  virtual ~CutsBySplitting() = default;
  /// The same body on the same mesh as read, its cells split along `pieces`
  /// (fem: split): its nodes are this one's (new copies after them), so a
  /// state carries over exactly.
  virtual std::unique_ptr<DiscreteBody> split_along(const Scene& scene, std::span<const CutPiece> pieces) const = 0;
  /// `field` (over this body's dofs) on `next` (made by split_along): each
  /// node of a copy takes the value of the node it had in the copy of the
  /// same cell that holds its fragment. Nothing is interpolated.
  virtual Vector carried_to(const DiscreteBody& next, const Vector& field) const = 0;
};

class EnrichmentLattices {
 public:
  virtual ~EnrichmentLattices() = default;
  /// The Enrichment Grids' phi, one per grid-enriched cut present.
  virtual std::vector<LatticeSnapshot> enrichment_lattices() const = 0;
};

class DiscretizationFigures {
 public:
  virtual ~DiscretizationFigures() = default;
  /// Figures of the discretization as it stands, into the summary's extras.
  virtual void add_figures(std::map<std::string, double>& extras) const = 0;
};

class ElementStepBound {
 public:
  virtual ~ElementStepBound() = default;
  /// A safe central-difference step with the lumped mass (s), from element
  /// frequency bounds at the undeformed state (over this rank's cells when
  /// the body is partitioned: the smallest over the ranks is the bound).
  virtual double critical_time_step() const = 0;
};

class MeshedBody {
 public:
  virtual ~MeshedBody() = default;
  virtual const Mesh& mesh() const = 0;
  /// Whether cell c integrates only a fragment of itself (a split cell's copy, fem: split).
  virtual bool fragment_cell(Index c) const { return false; }
};

/// A row-major CSR matrix's arrays (full symmetric storage), as a body sees them.
struct CsrView {
  Index rows = 0;
  const Index* outer = nullptr;  // rows + 1
  const Index* inner = nullptr;  // column of each value, sorted within a row
  double* values = nullptr;
};

class MatrixAssembly {
 public:
  virtual ~MatrixAssembly() = default;
  /// The same as tangent(u, add_into(matrix), f), to round-off, without
  /// searching the matrix for each block's places (FEM: a table built once per
  /// pattern, which must not change in place once seen; EFG: node by node).
  /// `matrix` holds every block tangent() writes. A body may copy its
  /// symmetric part's lower half from the upper (EFG): the matrix must hold a
  /// symmetric matrix before, as the solvers' zeroed one is.
  virtual void add_tangent_into(const Vector& u, const CsrView& matrix, Vector* f) const = 0;
};

/// A body that, under several MPI ranks, computes only its rank's part:
/// internal_force, tangent, add_tangent_into, strain_energy and both masses
/// then hold the contributions of this rank's cells alone (partial sums over
/// all dofs), which MechanicalSystem adds up across the ranks. Loads,
/// constraints, probes and snapshots stay whole on every rank.
class PartitionedAssembly {
 public:
  virtual ~PartitionedAssembly() = default;
  /// Whether the body computes a part (false: the whole, as a serial run does).
  virtual bool partitioned() const = 0;
  /// [begin, end) of the nodes this rank owns: their rows are its rows.
  virtual std::pair<Index, Index> owned_nodes() const = 0;
  /// Its own nodes and every node its cells touch (ghosts), sorted.
  virtual const std::vector<Index>& touched_nodes() const = 0;
};

/// A partitioned body whose rank holds a piece of it (own nodes, then the
/// ghosts its cells touch) and computes on vectors over the piece's dofs, so
/// that an explicit step needs the whole vectors on no rank: its forces are
/// summed between the ranks that share a ghost (solvers/ghost_exchange.h).
class PieceLayout {
 public:
  virtual ~PieceLayout() = default;
  /// The global dof of each of the piece's dofs: the own ones first (this
  /// rank's rows, ascending), then the ghosts'.
  virtual const std::vector<Index>& piece_dofs() const = 0;
  virtual Index own_dof_count() const = 0;
  /// This rank's cells' internal force at the piece's u, over the piece's dofs (partial at shared nodes).
  virtual void piece_internal_force(const Vector& u, Vector& f) const = 0;
  /// This rank's cells' lumped mass, over the piece's dofs.
  virtual Vector piece_lumped_mass() const = 0;
  /// The whole external force's entries at the piece's dofs (complete, not a part).
  virtual void piece_external_force(double t, Vector& f) const = 0;
};

/// The body's capability C, or null.
template <class C>
const C* capability(const DiscreteBody& body) {
  return dynamic_cast<const C*>(&body);
}
template <class C>
C* capability(DiscreteBody& body) {
  return dynamic_cast<C*>(&body);
}

}  // namespace kerf
