#include "discretization/body_factory.h"

#include <algorithm>
#include <string>

#include "core/check.h"
#include "discretization/fem/fem_body.h"
#include "discretization/fem/fem_piece_body.h"
#include "discretization/meshless/efg_body.h"
#include "discretization/meshless/nodal_body.h"
#include "geometry/box_mesher.h"
#include "geometry/cut_cell_removal.h"
#include "geometry/cut_surface.h"
#include "geometry/lattice_cells.h"
#include "geometry/mesh_from_first_rank.h"
#include "geometry/mesh_ordering.h"
#include "geometry/mid_edge_nodes.h"
#include "geometry/msh_reader.h"
#include "problem/body_plan.h"

namespace kerf {
namespace {

/// The mesh of the scene's box (gmsh at `size`, of cells of `order`,
/// conforming to and opened along `cuts`; or the box's lattice at `size`
/// split into cells, `lattice`), or its mesh file as it stands, made by this process.
Mesh scene_mesh(const Scene& scene, int order, double size, bool lattice, std::vector<CutPiece> cuts = {}) {
  if (!scene.box) return read_msh(scene.mesh_file, scene.dimension);
  if (lattice) {
    KERF_CHECK(cuts.empty(), "discretization.fem.box_mesher: value 'lattice' cannot mesh the box anew along a cut "
                             "(fem: remesh); expected box_mesher: gmsh");
    Mesh cells = lattice_cells(scene.dimension, scene.box->min, scene.box->max, size);
    return order == 2 ? with_mid_edge_nodes(cells) : cells;
  }
  BoxMeshRequest request;
  request.cuts = std::move(cuts);
  request.dimension = scene.dimension;
  request.order = order;
  request.min = scene.box->min;
  request.max = scene.box->max;
  request.size = size;
  for (const RefineRegion& r : scene.discretization.refine) request.refine.push_back({r.box.min, r.box.max, r.size});
  return mesh_box(request);
}

/// FEM's mesh, made by this process: its cells are of the element the scene
/// asks, never silently another. A linear mesh file asked for quadratic
/// cells is raised (mid-edge nodes on its straight edges, as gmsh raises it); a
/// quadratic one asked for linear cells keeps its corners (edges
/// straightened). Either is said in the notes.
Mesh fem_mesh(const Scene& scene, std::vector<CutPiece> cuts, RunReport& report) {
  const ElementType element = scene.discretization.fem.element;
  const MeshPlan plan = body_plan(scene).mesh;
  const int order = plan.order;
  if (scene.box) return scene_mesh(scene, order, plan.size, plan.lattice, std::move(cuts));
  int file_order = order;
  Mesh mesh = read_msh(scene.mesh_file, scene.dimension, order == 2 ? MshOrder::second : MshOrder::as_in_file,
                       &file_order);
  const std::string asked = std::string("discretization.fem.element: ") + to_string(element) + " on the mesh file " +
                            scene.mesh_file + ", which holds " + (file_order == 1 ? "linear" : "quadratic") +
                            " cells: ";
  if (order == 2 && file_order == 1)
    report.notes.push_back(asked + "raised them to second order (mid-edge nodes on their straight edges)");
  if (order == 1 && mesh.order == 2) {
    mesh = corner_mesh(mesh);
    report.notes.push_back(asked + "their corner nodes were taken as linear cells (curved edges straightened)");
  }
  return mesh;
}

/// Under MPI, a body computes only its rank's cells, nodes or Gauss points
/// (contact splits its points too; meshless cuts change shape functions, not
/// the rows). Not a body that a growing cut rebuilds (FEM meshes it anew):
/// it runs whole on every rank, only the linear solve shared.
RankShare rank_share(const MpiContext& mpi, const Scene& scene, const CutTimeline& cuts) {
  const bool rebuilt = method_descriptor(scene.discretization.method).rebuilt_as_cut_grows && cuts.grows();
  return rebuilt ? RankShare{} : mpi.ranks;
}

/// A FEM body on this rank's piece of the scene's mesh, made and divided on
/// rank 0 (cells a cut removes are removed there first).
std::unique_ptr<DiscreteBody> make_fem_piece_body(const MpiContext& mpi, const Scene& scene, const CutTimeline& cuts,
                                                  double time, RunReport& report) {
  const std::vector<CutPiece> removed = cuts.fem_pieces(FemCut::remove, time);
  MeshPiece piece = mesh_piece_from_first_rank(mpi, [&] {
    Mesh mesh = fem_mesh(scene, cuts.fem_pieces(FemCut::remesh, time), report);
    if (!removed.empty()) report.cuts.removed_cells += remove_crossed_cells(mesh, removed);
    order_for_locality(mesh);
    return mesh;
  });
  report.add_stage("mesh");
  if (!removed.empty()) report.add_stage("cut cells removed");
  report.add_stage("mesh divided");
  report.parallel.mesh_divided = true;
  return std::make_unique<FemPieceBody>(scene, std::move(piece), mpi);
}

/// Under mpirun, a body kept whole on every rank says why in the run's notes (once: a growing cut builds it again).
void note_how_ranks_hold_the_body(const MpiContext& mpi, const BodyPlan& plan, RunReport& report) {
  const std::string& why = plan.whole_on_every_rank;
  if (!mpi.distributed() || why.empty()) return;
  const std::string note =
      "on " + std::to_string(mpi.ranks.count) + " MPI ranks the body is not divided among them: " + why;
  if (std::find(report.notes.begin(), report.notes.end(), note) == report.notes.end()) report.notes.push_back(note);
}

std::unique_ptr<DiscreteBody> make_meshless_body(const MpiContext& mpi, const Scene& scene, const BodyPlan& plan,
                                                 SharedCuts cuts, RunReport& report) {
  std::optional<Mesh> background;
  if (plan.mesh.made) {
    // The lattice's own cells are the same on every rank; gmsh's mesh is made once, on the first.
    const MeshPlan& m = plan.mesh;
    background = m.lattice ? scene_mesh(scene, 1, m.size, true)
                           : corner_mesh(mesh_from_first_rank(
                                 mpi, [&] { return scene_mesh(scene, m.order, m.size, false); }));
    order_for_locality(*background);
    report.add_stage("mesh");
  }
  const MeshlessOptions& options = scene.discretization.meshless;
  NodeSet nodes = plan.nodes_on_mesh ? mesh_nodes(*background, options.support)
                                     : lattice_nodes(scene.dimension, *scene.box, options.spacing,
                                                     scene.discretization.refine, options.support);
  report.add_stage("nodes");
  const RankShare share = rank_share(mpi, scene, *cuts);
  MeshlessDomain domain(scene, std::move(cuts), std::move(nodes), scene.box, std::move(background));
  report.add_stage("shape functions");
  if (scene.discretization.method == Method::nodal) return std::make_unique<NodalBody>(scene, std::move(domain), share);
  // The ranks' context only where the body is shared among them (its sums are collective).
  return std::make_unique<EfgBody>(scene, std::move(domain), share.distributed() ? mpi : MpiContext{share});
}

}  // namespace

std::unique_ptr<DiscreteBody> make_body(const Scene& scene, RunReport& report) {
  return make_body(scene, std::make_shared<const CutTimeline>(scene), report, 0.0);
}

std::unique_ptr<DiscreteBody> make_body(const Scene& scene, SharedCuts cuts, RunReport& report, double time,
                                        const MpiContext& mpi) {
  ScopedTimer timer(report.phases, Phase::setup);
  const BodyPlan plan = body_plan(scene);
  note_how_ranks_hold_the_body(mpi, plan, report);
  if (plan.method->meshless) return make_meshless_body(mpi, scene, plan, std::move(cuts), report);
  // The scene's cuts as they stand at `time`: `remesh` ones shape the mesh,
  // `remove` ones delete cells, `split` ones split them (in the body).
  const std::vector<CutPiece> removed = cuts->fem_pieces(FemCut::remove, time);
  if (mpi.distributed() && plan.divided_among_ranks())
    return make_fem_piece_body(mpi, scene, *cuts, time, report);
  // Made on rank 0 alone under mpirun (its notes are rank 0's: it writes the summary).
  Mesh mesh =
      mesh_from_first_rank(mpi, [&] { return fem_mesh(scene, cuts->fem_pieces(FemCut::remesh, time), report); });
  report.add_stage("mesh");
  if (!removed.empty()) {
    report.cuts.removed_cells += remove_crossed_cells(mesh, removed);
    report.add_stage("cut cells removed");
  }
  const std::vector<CutPiece> split = cuts->fem_pieces(FemCut::split, time);
  auto body = std::make_unique<FemBody>(scene, std::move(mesh), rank_share(mpi, scene, *cuts), split);
  record_split(*body, report);
  return body;
}

void record_split(const DiscreteBody& body, RunReport& report) {
  const auto* fem = dynamic_cast<const FemBody*>(&body);
  const CellSplit* split = fem ? fem->split() : nullptr;
  if (!split) return;
  report.cuts.split_cells = split->separated_cells;
  report.cuts.duplicated_nodes = split->duplicated_nodes;
  report.cuts.dropped_volume = split->dropped_measure;
  if (const FrontRefinement* front = fem->front()) {
    report.cuts.front_points += front->front_points;
    report.cuts.front_unresolved = front->unresolved_segments;
  }
  report.add_stage("cells split");
}

}  // namespace kerf
