#pragma once
// The finite-element discretization: tet4/tet10 (3D) or tri3/tri6 (2D plane
// strain, per metre of thickness) on a gmsh mesh, isoparametric, total Lagrangian.
// Shape-function gradients and quadrature weights are computed once. Linear
// cells may hold the law's bulk term at the nodes (fem.volumetric:
// averaged_nodal, nodal_bulk_average.h), which couples each node's star.
#include <vector>

#include "core/rank_share.h"
#include "core/run_report.h"
#include "discretization/body_capabilities.h"
#include "discretization/fem/nodal_bulk_average.h"
#include "discretization/fem/simplex_quadrature.h"
#include "geometry/boundary_facets.h"
#include "geometry/cell_schedule.h"
#include "geometry/mesh.h"
#include "geometry/point_location.h"
#include "problem/material.h"

namespace kerf {

class FemBody final : public DiscreteBody,
                      public SurfaceSampling,
                      public ElementStepBound,
                      public MeshedBody,
                      public MatrixAssembly,
                      public PartitionedAssembly {
 public:
  /// Builds loads and constraints from the scene; throws on a selection that
  /// takes nothing. With a distributed `share`, assembles only its rank's
  /// cells (PartitionedAssembly): an even split of the locality-ordered cells.
  FemBody(const Scene& scene, Mesh mesh, RankShare share = {});

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
  void add_tangent_into(const Vector& u, const CsrView& matrix, Vector* f) const override;

  bool partitioned() const override { return share_.distributed(); }
  std::pair<Index, Index> owned_nodes() const override { return owned_nodes_; }
  const std::vector<Index>& touched_nodes() const override { return touched_nodes_; }

 private:
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
  /// Element mass matrix (npc x npc, scalar: multiply by the identity per component).
  Eigen::MatrixXd element_scalar_mass(Index c) const;
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

  Mesh mesh_;
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
  int nqp_;                    // stiffness quadrature points per cell
  mutable std::vector<Index> pair_offsets_;        // npc^2 per cell
  mutable CsrView offsets_pattern_;                // the pattern pair_offsets_ was built for
  std::optional<NodalBulkAverage> bulk_average_;   // fem.volumetric: averaged_nodal
  mutable BulkAverages bulk_state_;                // its state at the last displacement asked
  mutable std::vector<Index> star_offsets_, star_offset_start_;
  mutable CsrView star_offsets_pattern_;
  std::vector<double> grad_;   // C * nqp * npc * dim: dN/dX at each point
  std::vector<double> wdet_;   // C * nqp: weight * det J (m^3, or m^2 in 2D)
  QuadratureRule mass_rule_;   // exact for N_a N_b
  Vector load_;                // dead loads: gravity, traction, pressure (N)
  std::vector<DirichletDof> dirichlet_;
};

}  // namespace kerf
