#pragma once
// What the two meshless bodies (EFG and nodal integration) share: the nodes and
// their k-d tree, the body's extent (a box, or a background mesh of tets or
// triangles), selections, point interpolation through MLS, strong constraints
// on nodal parameters, boundary loads integrated with MLS on the background
// mesh's boundary facets, the scene's cuts (enriched MLS weights), and the
// ParaView snapshot of the nodes.
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "discretization/body_capabilities.h"
#include "discretization/enrichment/cut_weights.h"
#include "discretization/fem/simplex_quadrature.h"
#include "discretization/meshless/boundary_quadrature.h"
#include "discretization/meshless/cut_cell_integration.h"
#include "discretization/meshless/node_cell_search.h"
#include "discretization/meshless/node_set.h"
#include "discretization/meshless/shape_table.h"
#include "discretization/meshless/smoothed_gradient.h"
#include "geometry/boundary_facets.h"
#include "geometry/cut_surface.h"
#include "geometry/mesh.h"
#include "problem/material.h"

namespace kerf {

/// Quadrature points on boundary facets (m), with weights (m^2; 2D: m) and outward unit normals.
struct BoundaryPoints {
  std::vector<Vec3> position;
  std::vector<Vec3> normal;
  std::vector<double> weight;
};

/// Condition numbers of the scaled moment matrices at the nodes (DESIGN.md:
/// watch them, near cuts and tips above all): a large one means a node's
/// shape functions rest on few or nearly coplanar neighbours.
struct MomentConditioning {
  double median = 0.0, max = 0.0;  // over all nodes
  double near_cut_max = 0.0;       // over the nodes whose weight a cut enriches
  double near_tip_max = 0.0;       // over the nodes whose support holds an end of a cut's front
  Index reduced_basis = 0;         // nodes left too few neighbours on their side of a cut (mls_spanned_linear)
};

class MeshlessDomain {
 public:
  /// `box`: the domain when it is a box; `background`: a simplex mesh covering
  /// the domain (needed for EFG cells, boundary loads and non-box domains).
  MeshlessDomain(const Scene& scene, SharedCuts cuts, NodeSet nodes, std::optional<Box> box,
                 std::optional<Mesh> background);
  ~MeshlessDomain();
  MeshlessDomain(MeshlessDomain&&) noexcept;

  const NodeSet& nodes() const { return nodes_; }
  MlsBasis basis() const { return basis_; }
  int dimension() const { return nodes_.dimension; }
  double domain_size() const { return domain_size_; }
  const Mesh& background() const;
  /// The mesh whose boundary facets bound the body: the background mesh, else the nodes' own cells.
  const Mesh& boundary_mesh() const { return background_ ? *background_ : nodes_.cells; }
  const BoundaryFacets& facets() const { return facets_; }
  /// Per node (dimension() entries each): the boundary term of the integration
  /// constraint, sum_b psi_I(x_b) n_b w_b over the closed boundary (the
  /// boundary facets and both faces of the cuts present), brought up to date
  /// by update_shapes_for_cuts.
  /// As of set-up or the last update_boundary_terms().
  const std::vector<double>& boundary_terms() const { return boundary_terms_; }
  /// Brings boundary_terms() to the cuts as they now stand (the faces of new
  /// pieces, the rows whose weights the growths since changed).
  void update_boundary_terms();
  /// Points of the closed boundary left out of boundary_terms() because no
  /// MLS fits there (every node hidden by a cut), counted at set-up and growths.
  Index boundary_points_singular() const { return boundary_singular_; }

  /// The cuts' weight enrichment of the nodes (null without a cut present).
  const CutWeights* enrichment() const { return enrichment_ && enrichment_->present() ? enrichment_.get() : nullptr; }
  /// Brings the cuts to time t. Returns the nodes whose enriched weight
  /// changed (sorted; empty when no piece appeared) after recomputing the
  /// rows of at_nodes() they touch whose factors changed (with smoothed
  /// gradients, every row they touch); `rows`, when given, receives those
  /// rows; `volumes` the nodes whose volume (and second moments) changed with
  /// the cells the new pieces cross (visible_dual_cells.h). `after_row`,
  /// when given, is called with each of those rows once it is recomputed
  /// (refresh_shape_rows: on the threads that recompute them).
  std::vector<Index> update_shapes_for_cuts(double t, std::vector<Index>* rows = nullptr,
                                            std::vector<Index>* volumes = nullptr,
                                            const std::function<void(Index)>& after_row = {});
  /// Nodal integration at a cut by the cells' parts (cut_cell_integration.h);
  /// empty `position` without such cells.
  using CutCellPoints = CutCellIntegration::Points;
  CutCellPoints cut_cell_points() const;
  /// Do cut_cell_points() change as the cuts grow?
  bool cut_cell_points_grow() const { return cut_cells_ && growing_; }
  /// For a growing cut, every group of nodes a point of cut_cell_points() may
  /// ever join, at any stage of the growth (the sparsity is fixed at set-up):
  /// per cell near the whole cut, the nodes whose support reaches the cell.
  void visit_cut_cell_reach(const std::function<void(std::span<const Index>)>& visit) const;
  /// NSNI's second moments of the nodes' cells, those a cut crosses split as
  /// the volumes are; null when no cut splits cells.
  const std::vector<Vec3>* split_second_moments() const {
    return cut_cells_ ? &cut_cells_->second_moment() : nullptr;
  }
  /// Does the support of one of these nodes cover a boundary-load quadrature
  /// point (then the load vector must be integrated again)?
  bool boundary_loads_touch(std::span<const Index> nodes) const;

  /// MLS shape functions of the nodes at `points`; a point whose moment matrix
  /// is singular is an error naming it (`what`) and the scene keys to change.
  /// When a cut grows, the table keeps its factors' gradients for refresh_rows.
  /// `group_size`: the points come in runs of that many that lie close
  /// together (a cell's Gauss points), whose neighbour search they share.
  ShapeTable shapes_at(std::span<const Vec3> points, const std::string& what, Index group_size = 1) const;
  /// The neighbour lists shapes_at would give `points` (the nodes whose
  /// supports cover each), without the shape functions.
  NeighborLists supports_covering(std::span<const Vec3> points, Index group_size = 1) const;
  /// Recomputes rows `rows` of a table shapes_at built at `points` with the cuts
  /// as they stand (update_shapes_for_cuts has brought them to t); returns the
  /// rows whose factors had changed, hence recomputed.
  std::vector<Index> refresh_rows(ShapeTable& table, std::span<const Vec3> points, std::span<const Index> rows,
                                  const std::string& what) const;
  /// Of `rows` (of a table at `points`, holding a node the latest growth
  /// changed), those whose factors it may have changed: where the growth left
  /// phi as it was and enriched no new node of the row, the row stays as it is.
  std::vector<Index> rows_the_growth_may_change(const ShapeTable& table, std::span<const Vec3> points,
                                                std::span<const Index> rows) const;
  /// The shape table at the nodes themselves (nodal integration points, output);
  /// with meshless.gradient: smoothed (nodal), its gradients are the cells' means.
  const ShapeTable& at_nodes() const { return at_nodes_; }

  MomentConditioning conditioning() const;

  /// Mean number of other nodes whose support covers a node.
  double mean_neighbors() const;
  std::vector<Index> select_nodes(const Selection& selection) const;
  std::optional<PointInterpolation> interpolation_at(const Vec3& x) const;
  /// The background mesh's boundary facets whose corners all lie in the
  /// selection; when `required`, throws (naming the scene line) if there are none.
  std::vector<Index> facets_in(const Selection& selection, bool required = true) const;
  /// Collapsed Gauss points (n per direction) on the straight facets.
  BoundaryPoints boundary_points(std::span<const Index> facets, int points_per_direction) const;
  /// `rule` (on the reference facet) on the straight facets.
  BoundaryPoints boundary_points(std::span<const Index> facets, const QuadratureRule& rule) const;

  /// Collapsed Gauss points on the facets with a corner in `region`, with their MLS interpolation.
  SurfaceSamples surface_samples(const Box& region, int points_per_direction) const;

  /// Constraints on the nodal parameters of the selected nodes, for the
  /// Dirichlet conditions `take` accepts; sorted by dof.
  std::vector<DirichletDof> nodal_constraints(const Scene& scene, bool (*take)(const BoundaryCondition&)) const;
  /// Adds the tractions and pressures of the scene (dead loads) into `load` (N).
  void add_boundary_loads(std::span<const BoundaryCondition> conditions, Vector& load) const;

  /// Nodes as VTK vertices with the MLS displacement u_h(x_I), Cauchy and von
  /// Mises stress at the nodes, support radius, nodal volume, condition number.
  void snapshot(const Vector& u, const MaterialLaw& law, BodySnapshot& out) const;
  std::vector<LatticeSnapshot> enrichment_lattices() const;

 private:
  std::string mls_remedy() const;
  /// The closed boundary's quadrature points on the facets: 3 points a
  /// direction where loads act (their rule), 2 elsewhere (the weak conditions' rule).
  BoundaryQuadrature closed_boundary_facets(const Scene& scene) const;
  BoundaryQuadrature cut_faces(Index cut, Index first_piece, Index end_piece) const;
  /// boundary_terms_ from scratch; for a growing cut, the points and their
  /// shape functions are kept to be updated.
  void build_boundary_terms(const Scene& scene);
  ShapeTable boundary_shapes_at(std::span<const Vec3> points) const;

  NodeSet nodes_;
  std::optional<Box> box_;
  std::optional<Mesh> background_;
  BoundaryFacets facets_;
  std::vector<char> background_on_boundary_;
  std::unique_ptr<SupportIndex> index_;
  std::unique_ptr<CutWeights> enrichment_;   // owns the scene's cuts (null without any)
  std::unique_ptr<PointIndex> load_points_;  // boundary-load quadrature points (growing cuts only)
  MlsBasis basis_;
  std::string error_context_;  // names the scene file and key in MLS errors
  bool growing_ = false;       // a cut grows: tables keep their factors' gradients
  double domain_size_;
  std::unique_ptr<SmoothedGradients> smoothing_;  // nodal with meshless.gradient: smoothed
  ShapeTable at_nodes_;  // smoothed gradients with smoothing_
  NeighborLists covered_;  // per node: the slots of at_nodes_ holding it (built at the first cut growth)
  std::vector<double> boundary_terms_;  // the integration constraint's boundary term, per node
  std::unique_ptr<NodeCellSearch> cell_search_;  // nodes_.cells by place (with cuts)
  std::vector<Index> faces_taken_;      // per cut: pieces whose faces are in boundary_terms_
  // A growing cut: the closed boundary's points, their shape functions and
  // per node the slots holding it (built at the first growth after a change).
  BoundaryQuadrature boundary_points_;
  ShapeTable boundary_shapes_;
  NeighborLists boundary_users_;
  std::vector<Index> boundary_slot_row_;
  std::vector<Index> boundary_pending_;  // nodes growths changed since the last update_boundary_terms
  mutable Index boundary_singular_ = 0;  // boundary points left out, no MLS there (set-up and growths)
  std::vector<Index> slot_row_;  // per slot of at_nodes_: its row (built with covered_)
  std::unique_ptr<CutCellIntegration> cut_cells_;  // nodal, direct gradients, cuts: the cells split by them
};

}  // namespace kerf
