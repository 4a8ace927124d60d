#pragma once
// A FEM body whose mesh is divided among the MPI ranks: this rank holds its
// piece (own cells and one layer of ghost cells, geometry/mesh_division.h)
// and a FemBody on it, and the solvers see the whole body: the dofs in the
// pieces' global node numbering, vectors over all of them, this rank's own
// cells' forces, matrices and masses (PartitionedAssembly: MechanicalSystem
// adds the ranks' parts up). The loads, constraints, selections and probes
// are the whole run's, each decided by the ranks that own the nodes and
// shared among them (collective calls, made alike on every rank). Of the
// whole it keeps only what is of the dofs' length, as the solvers' vectors
// are: the node positions and the loads.
#include <memory>
#include <vector>

#include "core/mpi_context.h"
#include "discretization/fem/fem_body.h"
#include "geometry/mesh_division.h"

namespace kerf {

class FemPieceBody final : public DiscreteBody,
                           public ElementStepBound,
                           public MatrixAssembly,
                           public PartitionedAssembly,
                           public PieceLayout {
 public:
  /// Collective: every rank builds its piece's body at once.
  FemPieceBody(const Scene& scene, MeshPiece piece, const MpiContext& mpi);

  int dofs_per_node() const override { return dim_; }
  Index node_count() const override { return total_nodes_; }
  Vec3 node_position(Index node) const override { return positions_[node]; }
  Index element_count() const override { return total_cells_; }
  double mean_neighbors() const override { return mean_neighbors_; }

  void visit_couplings(const CouplingVisitor& visit) const override;
  void internal_force(const Vector& u, Vector& f) const override;
  void tangent(const Vector& u, const BlockSink& sink, Vector* f) const override;
  double strain_energy(const Vector& u) const override { return body_->strain_energy(local(u)); }
  void use_definite_tangent(bool definite) override { body_->use_definite_tangent(definite); }
  bool is_linear() const override { return body_->is_linear(); }
  void begin_time_step(const Vector& u) override { body_->begin_time_step(local(u)); }

  Vector lumped_mass() const override;
  void consistent_mass(const BlockSink& sink) const override { body_->consistent_mass(to_global(sink)); }
  void external_force(double, Vector& f) const override { f = load_; }
  std::vector<DirichletDof> dirichlet(double) const override { return dirichlet_; }

  /// Collective.
  std::vector<Index> select_nodes(const Selection& selection) const override;
  /// Collective: the first rank whose piece holds x answers.
  std::optional<PointInterpolation> interpolation_at(const Vec3& x) const override;
  /// This rank's own cells (BodySnapshot::piece).
  void snapshot(const Vector& u, BodySnapshot& out) const override { body_->snapshot(local(u), out); }

  /// This rank's cells' blocks straight into the matrix's arrays (FemBody's own path).
  void add_tangent_into(const Vector& u, const CsrView& matrix, Vector* f) const override;

  /// Over this rank's cells (the caller takes the smallest over the ranks).
  double critical_time_step() const override { return body_->critical_time_step(); }

  bool partitioned() const override { return true; }
  std::pair<Index, Index> owned_nodes() const override { return {first_node_, first_node_ + own_nodes_}; }
  const std::vector<Index>& touched_nodes() const override { return touched_; }

  const std::vector<Index>& piece_dofs() const override { return piece_dofs_; }
  Index own_dof_count() const override { return dim_ * own_nodes_; }
  void piece_internal_force(const Vector& u, Vector& f) const override { body_->internal_force(u, f); }
  Vector piece_lumped_mass() const override { return body_->lumped_mass(); }
  void piece_external_force(double, Vector& f) const override { f = piece_load_; }

 private:
  /// The whole run's selection, global node numbers ascending; throws, as
  /// select_points does, when it takes no node anywhere. Collective.
  std::vector<Index> whole_selection(const Selection& selection) const;
  /// The same as this piece's nodes.
  std::vector<Index> piece_selection(const Selection& selection) const;
  /// This piece's node of global node g, or -1.
  Index local_node(Index g) const;
  Index global_dof(Index local_dof) const { return dim_ * global_node_[local_dof / dim_] + local_dof % dim_; }
  /// A whole vector's entries at this piece's dofs (into a kept buffer).
  const Vector& local(const Vector& u) const;
  /// A vector over this piece's dofs as a whole one (zero at the other
  /// dofs), into `whole` (no allocation once it is sized).
  void to_whole(const Vector& piece_values, Vector& whole) const;
  BlockSink to_global(const BlockSink& sink) const;
  /// Every rank's own rows of `piece_values` end to end: the whole vector. Collective.
  Vector joined_own_rows(const Vector& piece_values) const;
  /// Every node's position and the whole mesh's mean neighbour count (collective).
  void share_positions_and_neighbours(const Mesh& mesh);
  /// The loads and constraints of the whole run (collective).
  void share_loads_and_constraints(const Scene& scene);

  MpiContext mpi_;
  int dim_;
  Index own_nodes_, first_node_, total_nodes_, total_cells_;
  double domain_size_;
  double mean_neighbors_ = 0.0;     // the whole body's
  std::vector<Index> global_node_;  // per node of the piece
  std::vector<Vec3> piece_positions_;
  std::vector<char> on_boundary_;   // per node of the piece: exact for own nodes
  std::vector<Vec3> positions_;     // every node's, in the global numbering
  std::unique_ptr<FemBody> body_;
  std::vector<Index> touched_;      // global numbers, ascending
  Vector load_;
  std::vector<Index> piece_dofs_;   // the global dof of each of the piece's
  Vector piece_load_;               // load_ at the piece's dofs
  std::vector<DirichletDof> dirichlet_;
  mutable Vector local_u_, piece_force_;  // buffers of the calls made every step
};

}  // namespace kerf
