#pragma once
// Meshless nodal integration, the paper's method (after Muller et al. 2004):
// F at each node from the MLS gradients there, internal forces from the
// nodally integrated strain energy sum_I V_I psi(F_I), lumped mass rho V_I,
// constraints on the nodal parameters. Its zero-energy modes are held by a
// hourglass-type term on every node pair (I, J in the support of I):
//   e_IJ = u_J - u_I - (F_I - 1)(x_J - x_I),
//   E_stab = 1/2 sum_I sum_J k_IJ |e_IJ|^2,  k_IJ = c mu V_I w_IJ / (sum_J w_IJ |x_J - x_I|^2),
// which vanishes for every affine motion (so patch tests and rigid rotations of
// any size are untouched) and is quadratic in u; or, with
// meshless.stabilization: nsni, by the strain-gradient term of naturally
// stabilized nodal integration (natural_stabilization.h), which has no parameter.
//
// With meshless.vci: linear (integration_constraint.h) the forces are tested
// with grad psi_K + xi_K, so the integration constraint holds on any node
// set and across cuts; the strains (trial side) are the MLS ones. fix and
// displacement act on the boundary faces (weak_boundary_conditions.h), or
// with meshless.essential: parameters, on the selected nodes' parameters
// (the paper's way, inconsistent: MLS does not interpolate).
#include <utility>
#include <vector>

#include "core/rank_share.h"
#include "discretization/meshless/meshless_body.h"
#include "discretization/meshless/natural_stabilization.h"
#include "discretization/meshless/nodal_force_kernel.h"
#include "discretization/meshless/point_integration.h"
#include "discretization/meshless/weak_boundary_conditions.h"
#include "problem/material.h"

namespace kerf {

/// The stabilisation's per-slot stiffness k_IJ (N/m; 0 for J = I), and per
/// node sum_J k_IJ X_IJ (3 entries, N) and sum_J k_IJ X_IJ X_IJ^T (3 x 3
/// row-major, N m), X_IJ = x_J - x_I. Slots are those of the domain's
/// at_nodes() table. The levers k_IJ X_IJ are formed where used: a table of
/// them would double the bytes a force pass reads.
struct StabilizationPairs {
  std::vector<double> stiffness, lever_sum, lever_moment;
};

class NodalBody final : public MeshlessBody,
                        public CutsInShapeFunctions,
                        public PartitionedAssembly,
                        public WeakConstraints {
 public:
  /// The default c of the stabilisation (meshless.stabilization: true).
  static constexpr double default_stabilization = 0.1;

  /// With `share` across ranks the body computes this rank's part alone
  /// (PartitionedAssembly): the terms of an even split of the nodes (each
  /// node is its own integration point), which are also the rows it owns.
  NodalBody(const Scene& scene, MeshlessDomain domain, RankShare share = {});

  bool partitioned() const override { return share_.distributed(); }
  std::pair<Index, Index> owned_nodes() const override { return own_nodes_; }
  const std::vector<Index>& touched_nodes() const override { return touched_nodes_; }

  Index element_count() const override { return node_count(); }

  void visit_couplings(const CouplingVisitor& visit) const override;
  /// Not reentrant: two calls on one body must not run at the same time (per-thread scratch).
  void internal_force(const Vector& u, Vector& f) const override;
  void tangent(const Vector& u, const BlockSink& sink, Vector* f) const override;
  double strain_energy(const Vector& u) const override;
  bool symmetric_tangent() const override { return test_offsets_.empty(); }
  /// The tangent tested with the MLS gradients themselves (no VCI correction).
  void galerkin_tangent(const Vector& u, const BlockSink& sink) const override;
  Vec3 weak_reaction(const Vector& u, const Selection& selection) const override;
  const WeakBoundaryConditions* weak_conditions() const override { return constraints_.get(); }

  Vector lumped_mass() const override;
  void consistent_mass(const BlockSink& sink) const override;
  /// The rows the new pieces touch: shape functions, stabilisation pairs and,
  /// where a changed support covers a boundary load, the load vector.
  CutUpdate update_for_cuts(double t) override;
  /// Nitsche's alpha from the tangents at u (WeakBoundaryConditions::refresh_alpha).
  void begin_time_step(const Vector& u) override;

  /// With meshless.cut_cells: split, the cells at a cut integrated by their
  /// parts: how many, and with how many points.
  void add_figures(std::map<std::string, double>& extras) const override;

  /// Stabilisation energy alone (J), hourglass or NSNI: zero for affine displacement fields.
  double stabilization_energy(const Vector& u) const;
  /// f_int(u) by the baseline x86-64 form of the 3D pass (tests: it must
  /// agree with the vector unit's form).
  void internal_force_baseline(const Vector& u, Vector& f) const;
  /// Bytes one internal-force pass streams (tables once, u and each thread's
  /// force vector once): the pass's floor over a measured bandwidth.
  std::size_t force_pass_bytes() const;
  /// VCI's offsets ghat - grad psi, dim per slot of at_nodes (1/m); empty with vci: none.
  const std::vector<double>& test_offsets() const { return test_offsets_; }

 private:
  /// f_int in one pass over the nodes, each thread scattering into its own
  /// force vector (summed at the end: no atomics; the sum's order depends on
  /// the thread count only). 2D; 3D runs nodal_force_3d on the same tables.
  template <int Dim, bool Stabilized>
  void force_kernel(const Vector& u, Vector& f) const;
  NodalForceTables force_tables() const;
  /// Strain energy with stabilisation; the stabilisation's part into *stabilization.
  double energies(const Vector& u, double* stabilization) const;
  /// The stabilisation's stiffness on point I's neighbours (scalar per node pair) into `block`.
  void add_stabilization_block(Index I, std::vector<double>& block) const;
  /// The tangent tested with grad psi + `offsets` (dim per slot; empty: Galerkin).
  void assemble_tangent(const Vector& u, const BlockSink& sink, std::span<const double> offsets) const;

  void share_nodes(RankShare share);
  /// The cells at a cut integrated by their parts (MeshlessDomain::cut_cell_points), when there are any.
  void integrate_cut_cells();
  /// integrate_cut_cells() again (a cut grew); returns the nodes whose own point's weight changed.
  std::vector<Index> reintegrate_cut_cells();
  void add_cut_cell_forces(const Vector& u, Vector& f) const;
  double cut_cell_energy(const Vector& u) const;
  /// Node I's weight into body_load_ (its volume as it stands).
  void weigh_node(Index I);
  /// NSNI's moments: the cells' as the cuts split them.
  std::vector<Vec3> cell_moments() const;
  /// VCI's correction for the shape functions as they stand, and the
  /// integration constraint's residual recorded.
  void correct_test_gradients();

  RankShare share_;
  std::pair<Index, Index> own_nodes_;  // the nodes whose terms this rank computes (all in a serial run)
  std::vector<Index> touched_nodes_;   // those and their neighbours, sorted
  bool stabilized_;           // the hourglass term
  StabilizationPairs pairs_;  // empty without the hourglass term
  std::unique_ptr<NaturalStabilization> natural_;  // null unless stabilization: nsni
  Vector body_load_;          // gravity alone (N)
  mutable std::vector<double> thread_forces_;  // 2D pass
  std::vector<double> position4_;              // 3D pass: positions 4 to a node (aligned_32)
  mutable NodalForceScratch scratch_;          // 3D pass
  mutable PointSchedule schedule_;             // tangent assembly, built at its first call
  bool vci_;
  std::vector<double> test_offsets_;  // VCI's ghat - grad psi, dim per slot of at_nodes (empty without)
  std::unique_ptr<WeakBoundaryConditions> constraints_;  // null with essential: parameters
  // The nodes' own points' weights: their volumes, less the parts of the
  // cells at a cut that cut_points_ integrate (with their second moments).
  std::vector<double> point_volume_;
  std::vector<Vec3> rest_moments_;  // empty without cut_points_
  std::unique_ptr<PointIntegration> cut_points_;  // null without cells at a cut to integrate
  std::pair<Index, Index> own_cut_points_{0, 0};
  Index cut_cells_ = 0;
  mutable PointSchedule cut_schedule_;
  mutable std::vector<Mat3> cut_stress_;
  mutable Vector cut_force_;
};

}  // namespace kerf
