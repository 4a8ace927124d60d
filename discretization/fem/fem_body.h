#pragma once
// The finite-element discretization: tet4/tet10 (3D) or tri3/tri6 (2D plane
// strain, per metre of thickness) on a gmsh mesh, isoparametric, total Lagrangian.
// Shape-function gradients and quadrature weights are computed once. Linear
// cells may hold the law's bulk term at the nodes (fem.volumetric:
// averaged_nodal, nodal_bulk_average.h), which couples each node's star.
#include <functional>
#include <optional>
#include <vector>

#include "core/rank_share.h"
#include "core/run_report.h"
#include "discretization/body_capabilities.h"
#include "discretization/fem/front_refinement.h"
#include "discretization/fem/nodal_bulk_average.h"
#include "discretization/fem/simplex_quadrature.h"
#include "geometry/boundary_facets.h"
#include "geometry/cell_split.h"
#include "geometry/cell_schedule.h"
#include "geometry/mesh.h"
#include "geometry/point_location.h"
#include "problem/material.h"

namespace kerf {

/// One rank's piece of a mesh divided among the ranks (geometry/mesh_division.h),
/// as a FemBody on it sees it: its own cells and nodes come first.
struct FemPiece {
  Index own_cells = 0;  // cells [0, own_cells) are assembled here; the others are ghosts
  Index own_nodes = 0;  // nodes [0, own_nodes) are this rank's rows
  double domain_size = 0.0;  // the whole body's bounding-box diagonal (m)
  /// The whole run's selection as this piece's nodes (a collective call).
  std::function<std::vector<Index>(const Selection&)> select;
  /// Each node's number across the pieces: add_tangent_into writes into a
  /// matrix in those numbers.
  std::vector<Index> global_node;
};

class FemBody final : public DiscreteBody,
                      public SurfaceSampling,
                      public ElementStepBound,
                      public MeshedBody,
                      public CutsBySplitting,
                      public MatrixAssembly,
                      public PartitionedAssembly {
 public:
  /// Builds loads and constraints from the scene; throws on a selection that
  /// takes nothing. With a distributed `share`, assembles only its rank's
  /// cells (PartitionedAssembly): an even split of the locality-ordered cells.
  /// With `split_along` (fem: split), the cells those cut pieces separate are
  /// replaced by one copy per side (geometry/cell_split.h), each integrating
  /// its fragment; loads, selections and probes are taken on the mesh as read.
  FemBody(const Scene& scene, Mesh mesh, RankShare share = {}, std::span<const CutPiece> split_along = {});
  /// On one rank's piece of a divided mesh (its nodes and cells in the
  /// piece's order): assembles, integrates gravity into the mass and
  /// writes its own cells alone; loads and constraints act on every node of
  /// the piece (an own node's are then complete: every cell around it is in
  /// the piece), the nodes taken by `piece.select`. No selection or load is
  /// refused here for taking nothing: the whole run decides (loaded_faces).
  FemBody(const Scene& scene, Mesh mesh, FemPiece piece);

  /// On a piece: per boundary condition of the scene, the boundary faces of
  /// own cells its traction or pressure acts on (0 for the others).
  const std::vector<Index>& loaded_faces() const { return loaded_faces_; }

  /// The split (fem: split), or null.
  const CellSplit* split() const { return split_ ? &*split_ : nullptr; }
  /// fem.split_front: subdivide: how the mesh given was refined along the
  /// cut's front before the split (its mesh moved into outline()), or null.
  const FrontRefinement* front() const { return front_ ? &*front_ : nullptr; }
  std::unique_ptr<DiscreteBody> split_along(const Scene& scene, std::span<const CutPiece> pieces) const override;
  Vector carried_to(const DiscreteBody& next, const Vector& field) const override;

  int dofs_per_node() const override { return mesh_.dimension; }
  Index node_count() const override { return mesh_.node_count(); }
  Vec3 node_position(Index node) const override { return mesh_.nodes[node]; }
  Index element_count() const override { return mesh_.cell_count(); }
  double mean_neighbors() const override;

  void visit_couplings(const CouplingVisitor& visit) const override;
  void internal_force(const Vector& u, Vector& f) const override;
  void tangent(const Vector& u, const BlockSink& sink, Vector* f) const override;
  double strain_energy(const Vector& u) const override;
  bool is_linear() const override { return law_.is_linear(); }
  void use_definite_tangent(bool definite) override { law_.set_definite_tangent(definite); }

  Vector lumped_mass() const override;
  void consistent_mass(const BlockSink& sink) const override;
  void external_force(double t, Vector& f) const override;
  std::vector<DirichletDof> dirichlet(double t) const override { return dirichlet_; }

  std::vector<Index> select_nodes(const Selection& selection) const override;
  std::optional<PointInterpolation> interpolation_at(const Vec3& x) const override;
  void snapshot(const Vector& u, BodySnapshot& out) const override;

  SurfaceSamples surface_samples(const Box& region, int points_per_direction) const override;
  /// From element frequency bounds (the largest eigenvalue of each cell's
  /// stiffness over its lumped mass).
  double critical_time_step() const override;
  const Mesh& mesh() const override { return mesh_; }
  bool fragment_cell(Index c) const override { return split_ && !split_->whole(c); }
  /// On a piece, `matrix` is in the pieces' global numbering (FemPiece::global_node).
  void add_tangent_into(const Vector& u, const CsrView& matrix, Vector* f) const override;

  bool partitioned() const override { return share_.distributed(); }
  std::pair<Index, Index> owned_nodes() const override { return owned_nodes_; }
  const std::vector<Index>& touched_nodes() const override { return touched_nodes_; }

 private:
  /// `mesh` already in locality order (a body split again keeps its mesh as read).
  struct Ordered {};
  /// `previous`: a body on the same outline whose facets and locator are
  /// taken instead of built again (a growing cut's next split; not with
  /// split_front: subdivide, whose outline changes).
  FemBody(Ordered, const Scene& scene, Mesh mesh, RankShare share, std::span<const CutPiece> split_along,
          const FemBody* previous = nullptr, std::optional<FemPiece> piece = std::nullopt);
  /// The cells this body assembles and writes: its own on a piece, else all
  /// (a partitioned whole mesh's rank assembles its range of them).
  Index kept_cells() const { return piece_ ? piece_->own_cells : mesh_.cell_count(); }
  /// Receives each element's stiffness block with the element's index; thread-safe per element.
  using ElementSink = std::function<void(Index cell, std::span<const Index> dofs, std::span<const double> values)>;
  /// The bulk measure's state for one displacement: each cell's own m_e and
  /// dm/dF, the nodes' m_a, and each cell's mean of its nodes' m_a.
  struct BulkAverages {
    std::vector<double> own, node, cell_mean;
    std::vector<Mat3> gradient;
  };
  /// Fills `out` (sized once, then reused: a step allocates nothing).
  template <int Dim, int Npc>
  void bulk_averages(const Vector& u, BulkAverages& out) const;
  /// `averages`: the cells take the nodal mean of the bulk measure (null: their own).
  template <int Dim, int Npc>
  void element_loop(const Vector& u, const BulkAverages* averages, const ElementSink* sink, Vector* f,
                    double* energy) const;
  /// With `stars`, and the bulk term averaged at the nodes, the nodal term's
  /// stiffness goes to it for this rank's nodes. `standard`: every cell keeps its own bulk term.
  void loop(const Vector& u, const ElementSink* sink, Vector* f, double* energy,
            const NodalBulkAverage::StarSink* stars = nullptr, bool standard = false) const;
  /// Element mass matrix (npc x npc, scalar: multiply by the identity per
  /// component), over the cell's fragment (`whole`: over its parent).
  Eigen::MatrixXd element_scalar_mass(Index c, bool whole = false) const;
  /// Cell c's lumped (HRZ) masses: its consistent diagonal scaled to its
  /// total. A copy takes its parent's times its share of the parent's mass,
  /// so a tet4 copy keeps its parent's explicit step whatever its size
  /// (split_elements.md 3.3); a fragment's own diagonal would not.
  Eigen::VectorXd lumped_cell_mass(Index c) const;
  /// Cell c's quadrature in its reference coordinates: `whole`'s, or on a
  /// copy, `whole` moved onto its fragment (tet4/tri3 stiffness: one point,
  /// the gradients being constant).
  QuadratureRule cell_rule(Index c, const QuadratureRule& whole, bool constant_integrand = false) const;
  /// Each cell's shape-function gradients and weights at its points
  /// (`rule`, or a copy's rule on its fragment); whole cells that were whole
  /// in `previous` (the same outline) take its figures.
  void integrate_cells(const QuadratureRule& rule, const FemBody* previous);
  /// integrate_cells where every cell is whole and nothing is taken: the
  /// cells in parallel, the reference gradients computed once.
  void integrate_whole_cells(const QuadratureRule& rule);
  /// Appends the figures of the parent's cell if it is whole here; false if it is split.
  bool take_whole_cell(Index parent, std::vector<double>& grad, std::vector<double>& wdet) const;
  /// Each cell's Cauchy stress, the mean over its stiffness points.
  std::vector<Mat3> cell_stresses(const Vector& u) const;
  /// A point inside next's cell c (a copy of a child when child_reference is
  /// given: its nodes' coordinates in the parent), in the reference
  /// coordinates of its parent in this body's outline.
  Vec3 point_in_parent(const FemBody& next, Index c, std::span<const Vec3> child_reference) const;
  /// The mesh as read (refined along the front by split_front: subdivide):
  /// facets, selections and probes live on it.
  const Mesh& outline() const { return split_ ? original_ : mesh_; }
  /// The node of cell c (a copy of `parent`) at the parent's node `node`.
  Index copy_node(Index c, Index parent, Index node) const;
  /// The cells copying original cell p: [copies_of_[p], copies_of_[p + 1]).
  std::pair<Index, Index> copies_of(Index p) const;
  /// rho g integrated against each node's shape function, into load_.
  void add_gravity(const Vec3& gravity);
  /// Each cell's node pairs (a, b): where column dpn node_b starts in row
  /// dpn node_a, from the row's start; built for one pattern, kept for the next call.
  const std::vector<Index>& pair_offsets(const CsrView& matrix) const;
  /// The same for each node's star (star size^2 offsets per node, from star_offset_start_).
  const std::vector<Index>& star_offsets(const CsrView& matrix) const;
  /// fem.volumetric: averaged_nodal: the nodes' volumes and stars; refuses quadratic cells.
  void average_bulk_at_nodes(const Scene& scene);
  void build_loads(const Scene& scene);
  void build_constraints(const Scene& scene);
  /// This rank's cells, rows and touched nodes; the whole mesh on one rank.
  void share_cells(RankShare share);

  std::optional<FemPiece> piece_;         // on a piece of a divided mesh
  std::vector<Index> loaded_faces_;       // on a piece: per boundary condition
  std::optional<FrontRefinement> front_;  // split_front: subdivide: the given mesh's refinement
  Mesh original_;                    // fem: split: the mesh as read, or as refined along the front (else moved into mesh_)
  std::optional<CellSplit> split_;   // fem: split: the copies' parents, fragments, node origins
  std::vector<CutPiece> split_pieces_;  // fem: split: the cut as given (a probe's side)
  Mesh mesh_;                        // the cells integrated (copies, with fem: split)
  std::vector<Index> copies_start_;  // fem: split: per original cell + 1, its first copy
  BoundaryFacets facets_;
  RankShare share_;
  Index cell_begin_ = 0, cell_end_ = 0;       // this rank's cells (all on one rank)
  std::pair<Index, Index> owned_nodes_;       // this rank's rows' nodes
  std::vector<Index> touched_nodes_;          // nodes of this rank's cells, sorted
  CellSchedule schedule_;      // this rank's cells; ranges of one phase share no node: parallel without conflicts
  std::vector<char> on_boundary_;
  CellLocator locator_;        // interpolation_at: probes, and a state carried to a new mesh
  MaterialLaw law_;
  double density_;
  double domain_size_;
  int npc_;                    // nodes per cell
  std::vector<Index> point_start_;  // per cell + 1: its stiffness points in grad_, wdet_
  mutable std::vector<Index> pair_offsets_;        // npc^2 per cell
  mutable CsrView offsets_pattern_;                // the pattern pair_offsets_ was built for
  std::optional<NodalBulkAverage> bulk_average_;   // fem.volumetric: averaged_nodal
  mutable BulkAverages bulk_state_;                // its state at the last displacement asked
  mutable std::vector<Index> star_offsets_, star_offset_start_;
  mutable CsrView star_offsets_pattern_;
  std::vector<double> grad_;   // points * npc * dim: dN/dX at each point
  std::vector<double> wdet_;   // points: weight * det J (m^3, or m^2 in 2D)
  QuadratureRule mass_rule_;   // exact for N_a N_b
  std::vector<double> mass_N_, mass_dN_;  // its shape values and reference gradients, point after point
  Vector load_;                // dead loads: gravity, traction, pressure (N)
  std::vector<DirichletDof> dirichlet_;
};

}  // namespace kerf
