#include "app/resource_estimate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "core/check.h"
#include "discretization/fem/simplex_quadrature.h"
#include "discretization/meshless/efg_cell_rules.h"
#include "geometry/lattice_cells.h"
#include "problem/body_plan.h"

namespace kerf {
namespace {

// Fitted to gmsh's meshes of boxes (cells and vertices per h^d of volume and
// per h^(d-1) of boundary) and to measured peak memory; the test holds them.
constexpr double tets_per_volume = 4.5, tets_per_area = 1.0;
constexpr double tet_vertices_per_volume = 0.63, tet_vertices_per_area = 1.0;
constexpr double tris_per_area = 2.31, tris_per_length = 0.27;
constexpr double tri_vertices_per_area = 1.15, tri_vertices_per_length = 0.64;
// The process, and each module a run loads (core/module_loader.h): the
// resident memory loading it alone added (a program dlopening it,
// 2026-12-04). A run that loads all three has the 110 MB base fitted before
// kerf loaded them on demand.
constexpr double process_mb = 22.0;
constexpr double gmsh_module_mb = 47.0, petsc_module_mb = 29.0, vtk_module_mb = 12.0;
constexpr double gmsh_bytes_per_cell = 1500.0;   // gmsh's own structures while it meshes
constexpr double shape_table_copies = 3.3;       // nodal: tables at nodes and boundary points, pairs, neighbour lists
// EFG: the Gauss points' table and stresses; its nodes' and boundary points'
// tables are small beside it. Fitted to the scaling study's EFG cantilever
// (198k points: 845 MB measured on one rank, 1 493 estimated with nodal's
// 3.3 copies, 988 with 1.3) and the regression cases (0.86-1.24 with 1.3).
constexpr double efg_table_copies = 1.3;
constexpr double smoothed_bytes_per_node = 45e3; // smoothing-cell samples and their shape functions
constexpr double matrix_copies = 3.0;            // K (pattern and values), A on the free dofs, the preconditioner
// A rank's share of the matrix and its algebraic multigrid, over 1/ranks of
// one rank's (the 513k-dof static tet10 block, its mesh divided;
// results/scaling.md, second run of 2026-11-29): 1.96, 1.96, 1.93 at 2, 3, 4
// ranks with PETSc's GAMG options as the scene writes them (its parallel
// triple product), 0.92, 0.90, 0.93 with kerf's own when the scene leaves
// solve.petsc out (petsc_rank_options).
constexpr double parallel_matrix_overhead_as_written = 1.95;
constexpr double parallel_matrix_overhead_kerf_options = 0.92;
constexpr double factor_fill_3d = 0.17;          // nnz(L) / nnz(K) per dofs^(1/3) (nested dissection)
constexpr double factor_fill_2d = 0.4;           // nnz(L) / nnz(K) per log2(dofs)

/// The size the scene asks for at x: the smallest refine box's holding x, or `size`.
double size_at(const Scene& scene, double size, const Vec3& x) {
  double h = size;
  for (const RefineRegion& r : scene.discretization.refine)
    if (r.size > 0.0 && r.box.contains(x, 0.0)) h = std::min(h, r.size);
  return h;
}

/// The box cut at every refine box's faces along each axis: between two
/// neighbouring cuts the size is constant.
std::array<std::vector<double>, 3> size_cuts(const Scene& scene) {
  const Box& box = *scene.box;
  std::array<std::vector<double>, 3> cuts;
  for (int i = 0; i < 3; ++i) {
    cuts[i] = {box.min[i], box.max[i]};
    if (i == 2 && scene.dimension == 2) break;
    for (const RefineRegion& r : scene.discretization.refine)
      for (double c : {r.box.min[i], r.box.max[i]}) cuts[i].push_back(std::clamp(c, box.min[i], box.max[i]));
    std::sort(cuts[i].begin(), cuts[i].end());
    cuts[i].erase(std::unique(cuts[i].begin(), cuts[i].end()), cuts[i].end());
  }
  if (scene.dimension == 2) cuts[2] = {0.0, 1.0};
  return cuts;
}

/// The integral of h^-d over the domain (cells of the local size it holds)
/// and of h^-(d-1) over its boundary, h piecewise constant as the refine
/// boxes set it.
struct SizeCounts {
  double volume = 0.0, boundary = 0.0;
};

/// The volume (area in 2D) two boxes share.
double overlap_volume(const Box& a, const Box& b, int d) {
  double v = 1.0;
  for (int i = 0; i < d; ++i) v *= std::max(0.0, std::min(a.max[i], b.max[i]) - std::max(a.min[i], b.min[i]));
  return v;
}

/// Past this many refine boxes the exact count (a grid of up to (2B+1)^d
/// pieces, each testing every box) would cost more than the run it guards.
constexpr std::size_t exact_refine_limit = 24;

/// Each refine box counted on its own, overlaps twice: an over-estimate.
SizeCounts counts_box_by_box(const Scene& scene, double size) {
  const int d = scene.dimension;
  const Box& domain = *scene.box;
  const Vec3 e = domain.max - domain.min;
  SizeCounts n;
  n.volume = (d == 3 ? e.prod() : e.x() * e.y()) / std::pow(size, d);
  n.boundary = d == 3 ? 2.0 * (e.x() * e.y() + e.y() * e.z() + e.z() * e.x()) / (size * size)
                      : 2.0 * (e.x() + e.y()) / size;
  for (const RefineRegion& r : scene.discretization.refine) {
    if (!(r.size > 0.0 && r.size < size)) continue;
    n.volume += overlap_volume(r.box, domain, d) * (std::pow(r.size, -d) - std::pow(size, -d));
  }
  return n;
}

SizeCounts counts_of_size(const Scene& scene, double size) {
  if (scene.discretization.refine.size() > exact_refine_limit) return counts_box_by_box(scene, size);
  const int d = scene.dimension;
  const auto cuts = size_cuts(scene);
  SizeCounts n;
  for (std::size_t a = 0; a + 1 < cuts[0].size(); ++a)
    for (std::size_t b = 0; b + 1 < cuts[1].size(); ++b)
      for (std::size_t c = 0; c + 1 < cuts[2].size(); ++c) {
        const Vec3 lo(cuts[0][a], cuts[1][b], cuts[2][c]), hi(cuts[0][a + 1], cuts[1][b + 1], cuts[2][c + 1]);
        const Vec3 extent = hi - lo;
        const double h = size_at(scene, size, 0.5 * (lo + hi));
        n.volume += (d == 3 ? extent.prod() : extent.x() * extent.y()) / std::pow(h, d);
        // This cell's faces on the domain's boundary.
        const std::size_t index[3] = {a, b, c};
        for (int i = 0; i < d; ++i) {
          const bool first = index[i] == 0, last = index[i] + 2 == cuts[i].size();
          const double face = d == 3 ? extent.prod() / extent[i] : extent[1 - i];
          n.boundary += (first + last) * face / std::pow(h, d - 1);
        }
      }
  return n;
}

/// The cells of gmsh's transitions: outside each refine box the size grows
/// linearly over twice the base size (box_mesher's Thickness) until it meets
/// the size around the box; over a face of area A this holds about
/// A * T / ((d-1)(h0 - h)) * (h^-(d-1) - h_out^-(d-1)) cells.
double transition_cells(const Scene& scene, double size) {
  const int d = scene.dimension;
  const Box& domain = *scene.box;
  double cells = 0.0;
  for (const RefineRegion& r : scene.discretization.refine) {
    if (!(r.size > 0.0 && r.size < size)) continue;
    Box b{r.box.min.cwiseMax(domain.min), r.box.max.cwiseMin(domain.max)};
    const Vec3 extent = b.max - b.min;
    if ((extent.head(d).array() <= 0.0).any()) continue;
    for (int i = 0; i < d; ++i)
      for (int side = 0; side < 2; ++side) {
        const double at = side ? b.max[i] : b.min[i];
        if (at <= domain.min[i] || at >= domain.max[i]) continue;  // on the domain's boundary
        Vec3 outside = 0.5 * (b.min + b.max);
        outside[i] = at + (side ? 1.0 : -1.0) * 1e-9 * (1.0 + std::abs(at));
        const double around = size_at(scene, size, outside);
        if (around <= r.size) continue;
        const double area = d == 3 ? extent.prod() / extent[i] : extent[1 - i];
        const double thickness = 2.0 * size;
        cells += area * thickness / ((d - 1) * (size - r.size)) *
                 (std::pow(r.size, 1 - d) - std::pow(around, 1 - d));
      }
  }
  return cells;
}

struct MeshCounts {
  double cells = 0.0, nodes = 0.0;
};

MeshCounts mesh_counts(const Scene& scene, double size, int order) {
  const SizeCounts n = counts_of_size(scene, size);
  const double volume = n.volume + transition_cells(scene, size);
  MeshCounts m;
  if (scene.dimension == 3) {
    m.cells = tets_per_volume * volume + tets_per_area * n.boundary;
    m.nodes = tet_vertices_per_volume * volume + tet_vertices_per_area * n.boundary;
    if (order == 2) m.nodes += 1.4 * m.cells;  // about 1.4 edges a tetrahedron
  } else {
    m.cells = tris_per_area * volume + tris_per_length * n.boundary;
    m.nodes = tri_vertices_per_area * volume + tri_vertices_per_length * n.boundary;
    if (order == 2) m.nodes += 1.5 * m.cells;
  }
  return m;
}

/// Points of a lattice at `spacing` over the box, faces included (as node_set.cpp lays them).
double lattice_points(const Box& box, double spacing, int d) {
  const std::array<int, 3> n = lattice_intervals(d, box.min, box.max, spacing);
  double points = 1.0;
  for (int i = 0; i < d; ++i) points *= n[i] + 1.0;
  return points;
}

/// Nodes of the lattice at `spacing` with each refine box's own lattice
/// (node_set.cpp): a box's points, less those a finer box's lattice holds
/// too; the base's, less those inside the boxes.
double lattice_nodes(const Scene& scene, double spacing) {
  const int d = scene.dimension;
  const Box& domain = *scene.box;
  double nodes = lattice_points(domain, spacing, d);
  const auto& refine = scene.discretization.refine;
  for (const RefineRegion& r : refine) {
    if (!(r.size > 0.0 && r.size < spacing)) continue;
    const Box box{r.box.min.cwiseMax(domain.min), r.box.max.cwiseMin(domain.max)};
    if (overlap_volume(box, box, d) <= 0.0) continue;
    double own = lattice_points(box, r.size, d) - overlap_volume(box, box, d) / std::pow(spacing, d);
    for (const RefineRegion& finer : refine)
      if (finer.size > 0.0 && finer.size < r.size) own -= overlap_volume(box, finer.box, d) / std::pow(r.size, d);
    nodes += std::max(0.0, own);
  }
  return nodes;
}

/// The FEM body's stiffness points a cell (its element's quadrature).
double points_per_cell(const ElementDescriptor& element) {
  return static_cast<double>(simplex_quadrature(element.dimension, element.stiffness_degree).points.size());
}

/// The body's counts: nodes, points, and the node pairs a matrix row couples,
/// of the body the factory builds (body_plan.h).
void estimate_body(const Scene& scene, ResourceEstimate& e, double& coupled) {
  const int d = scene.dimension;
  const BodyPlan plan = body_plan(scene);
  // A meshless body's nodes are the mesh's corners (corner_mesh), whatever the element's order.
  const int order = plan.method->meshless ? 1 : plan.mesh.order;
  MeshCounts mesh;
  if (plan.mesh.lattice) {
    const std::array<int, 3> intervals = lattice_intervals(d, scene.box->min, scene.box->max, plan.mesh.size);
    mesh.cells = lattice_cell_count(d, intervals);
    mesh.nodes = lattice_points(*scene.box, plan.mesh.size, d) + (order == 2 ? lattice_edge_count(d, intervals) : 0.0);
  } else if (plan.mesh.made) {
    mesh = mesh_counts(scene, plan.mesh.size, order);
  }
  e.mesh_cells = mesh.cells, e.mesh_nodes = mesh.nodes;
  e.gmsh_meshes = plan.mesh.made && !plan.mesh.lattice;
  e.size_key = plan.size_key, e.size = plan.size;
  if (!plan.method->meshless) {
    const ElementDescriptor& element = element_descriptor(scene.discretization.fem.element);
    e.nodes = mesh.nodes;
    e.points = mesh.cells * points_per_cell(element);
    coupled = element.coupled_nodes;
    return;
  }
  const MeshlessOptions& o = scene.discretization.meshless;
  e.nodes = plan.nodes_on_mesh ? mesh.nodes : lattice_nodes(scene, o.spacing);
  e.points = plan.method->integration == Integration::background_cells
                 ? mesh.cells * static_cast<double>(efg_cell_rule(o, d).points.size())
                 : e.nodes;
  // Nodes in a support, three quarters of a full ball's (the boundary's share, as measured).
  const double ball =
      d == 3 ? 4.0 / 3.0 * std::numbers::pi * std::pow(o.support, 3) : std::numbers::pi * o.support * o.support;
  e.neighbors = 0.75 * ball;
  coupled = std::pow(2.0, d) * e.neighbors;  // nodes sharing a point: within two supports
}

/// When one refine box holds most of the cells, its size is what to change:
/// the key names it (discretization.refine.N.size), not the base size.
void blame_the_finest_share(const Scene& scene, ResourceEstimate& e) {
  const int d = scene.dimension;
  const double total = counts_of_size(scene, e.size).volume;
  const auto& refine = scene.discretization.refine;
  for (std::size_t i = 0; i < refine.size(); ++i) {
    const RefineRegion& r = refine[i];
    if (!(r.size > 0.0 && r.size < e.size)) continue;
    const Box box{r.box.min.cwiseMax(scene.box->min), r.box.max.cwiseMin(scene.box->max)};
    if (overlap_volume(box, box, d) / std::pow(r.size, d) > 0.5 * total) {
      e.size_key = "discretization.refine." + std::to_string(i) + ".size";
      e.size = r.size;
      return;
    }
  }
}

/// The Enrichment Grids: each cut's bounding box, padded by a support, at its grid spacing.
double grid_points(const Scene& scene) {
  if (!method_descriptor(scene.discretization.method).meshless) return 0.0;
  const double pad = scene.discretization.meshless.support * scene.discretization.meshless.spacing;
  double points = 0.0;
  for (const Cut& cut : scene.cuts) {
    if (cut.enrichment != Enrichment::grid || cut.vertices.empty()) continue;
    Vec3 lo = cut.vertices.front(), hi = lo;
    for (const Vec3& v : cut.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    double n = 1.0;
    for (int i = 0; i < scene.dimension; ++i) n *= (hi[i] - lo[i] + 2.0 * pad) / cut.grid_spacing + 1.0;
    points += n;
  }
  return points;
}

int written_steps(const Scene& scene) {
  if (scene.output.vtk_every <= 0) return 0;
  if (scene.solve.analysis == Analysis::static_analysis) return scene.solve.load_steps + 1;
  const double steps = std::max(1.0, std::round(scene.solve.duration / scene.solve.dt));
  return static_cast<int>(std::min(steps / scene.output.vtk_every, 1e9)) + 1;
}

/// The process and the modules the run loads: gmsh where it makes a mesh (a mesh file counted alike),
/// PETSc for MPI ranks or its solver, VTK for ParaView's files.
double base_mb(const Scene& scene, const ResourceEstimate& e) {
  double mb = process_mb;
  if (e.gmsh_meshes) mb += gmsh_module_mb;
  if (e.ranks > 1 || scene.solve.linear_solver == LinearSolverKind::petsc) mb += petsc_module_mb;
  if (scene.output.vtk_every > 0) mb += vtk_module_mb;
  return mb;
}

/// The run's memory beyond the process's base (MB), by how the MPI ranks hold it.
struct MemoryParts {
  double meshing = 0.0;  // gmsh's structures while it meshes (rank 0's alone under mpirun)
  double mesh = 0.0;     // the mesh's arrays
  double tables = 0.0;   // meshless shape tables and their kin (nodal: whole on every rank; EFG: divided)
  double matrix = 0.0;   // the matrix's copies and its factor or preconditioner: the ranks share it
  double whole = 0.0;    // the Enrichment Grids' columns; the state and work vectors: whole on every rank
  double sum() const { return meshing + mesh + tables + matrix + whole; }
};

MemoryParts memory_parts(const Scene& scene, const ResourceEstimate& e) {
  const int d = scene.dimension;
  constexpr double mb = 1048576.0;
  MemoryParts m;
  m.meshing = e.gmsh_meshes ? gmsh_bytes_per_cell * e.mesh_cells / mb : 0.0;
  m.mesh = 8.0 * e.mesh_cells * (d + 1) * 2.0 / mb;
  const double copies = scene.discretization.method == Method::efg ? efg_table_copies : shape_table_copies;
  double tables = copies * e.points * e.neighbors * (8.0 * (1 + d) + 8.0);
  if (scene.discretization.method == Method::nodal && scene.discretization.meshless.gradient == NodalGradient::smoothed)
    tables += smoothed_bytes_per_node * e.nodes;
  // NSNI: d x d second derivatives a slot of the nodes' table, and d moments a node.
  if (scene.discretization.method == Method::nodal &&
      scene.discretization.meshless.stabilization == NodalStabilization::nsni)
    tables += 8.0 * d * d * e.nodes * e.neighbors + 8.0 * d * e.nodes;
  // EFG's stiffness rows read the law's dP/dF at each point, kept a point unless the law is linear.
  if (scene.discretization.method == Method::efg && scene.solve.solves_linear_systems() &&
      scene.material.model != MaterialModel::linear)
    tables += 81.0 * 8.0 * e.points;
  m.tables = tables / mb;
  // A nonlinear body's factor, once stale, preconditions CG: with its single-precision
  // copy, from the last 8 solutions (solvers/solution_history.h).
  const bool stale_factor_cg = scene.material.model != MaterialModel::linear && e.factor_nonzeros > 0;
  const double factor_bytes = stale_factor_cg ? 12.0 : 8.0, vectors = stale_factor_cg ? 38.0 : 30.0;
  m.matrix = (matrix_copies * 12.0 * e.nonzeros + factor_bytes * e.factor_nonzeros) / mb;
  m.whole = (64.0 * e.grid_points + 8.0 * vectors * e.dofs) / mb;  // the grid's columns; the state and work vectors
  return m;
}

/// The largest rank's peak when `ranks` share the run. Rank 0 makes the mesh
/// (gmsh) before any matrix exists. A divided mesh (body_plan) leaves each
/// rank its piece; otherwise the mesh is whole on every rank, and so are the
/// tables but EFG's Gauss points'.
/// Either way the ranks share the matrix, at parallel_matrix_overhead.
double memory_mb_per_rank(const Scene& scene, const ResourceEstimate& e, const MemoryParts& m, int ranks) {
  const double base = base_mb(scene, e);
  if (ranks <= 1) return base + m.sum();
  const double parallel_matrix_overhead =
      scene.solve.petsc_written ? parallel_matrix_overhead_as_written : parallel_matrix_overhead_kerf_options;
  if (body_plan(scene).divided_among_ranks())
    return base + std::max(m.meshing + m.mesh, (m.mesh + m.matrix) * parallel_matrix_overhead / ranks + m.whole);
  // EFG: each rank holds its own cells' Gauss points (the nodes' tables, small beside them, are whole).
  const double tables = scene.discretization.method == Method::efg ? m.tables / ranks : m.tables;
  return base +
         std::max(m.meshing + m.mesh, m.mesh + tables + m.whole + m.matrix * parallel_matrix_overhead / ranks);
}

}  // namespace

ResourceEstimate estimate_resources(const Scene& scene, int ranks) {
  ResourceEstimate e;
  e.ranks = ranks;
  if (!scene.box) return e;  // a mesh file: its counts are in the file, not estimated here
  const int d = scene.dimension;
  double coupled = 0.0;
  estimate_body(scene, e, coupled);
  blame_the_finest_share(scene, e);
  e.dofs = d * e.nodes;
  if (scene.solve.solves_linear_systems()) {  // central differences assemble no matrix (Lanczos is matrix-free)
    e.nonzeros = e.dofs * d * coupled;
    const bool direct = linear_backend(scene.solve.linear_solver).direct;
    const double fill = d == 3 ? factor_fill_3d * std::cbrt(e.dofs) : factor_fill_2d * std::log2(e.dofs + 2.0);
    if (direct) e.factor_nonzeros = e.nonzeros * std::max(1.0, fill);
  }
  e.grid_points = grid_points(scene);
  // Each written step (measured on block_drop's .vtu, 285 bytes a node with its
  // 3.8 cells a node): the point arrays, about 120 bytes a node, and the
  // cells with their arrays, about 50 bytes a cell.
  e.output_mb_per_step = (120.0 * e.nodes + 50.0 * e.mesh_cells) / 1048576.0;
  e.output_mb = e.output_mb_per_step * written_steps(scene);
  const MemoryParts parts = memory_parts(scene, e);
  e.memory_mb = base_mb(scene, e) + parts.sum();
  e.memory_mb_per_rank = memory_mb_per_rank(scene, e, parts, ranks);
  return e;
}

std::string describe(const ResourceEstimate& e) {
  std::ostringstream out;
  out.precision(3);
  if (e.size_key.empty()) return "estimate: none (the domain is a mesh file; its own counts decide)\n";
  out << "estimate (from the scene, set by " << e.size_key << " = " << e.size << "):\n"
      << "  mesh cells " << e.mesh_cells << ", mesh nodes " << e.mesh_nodes << "\n"
      << "  nodes " << e.nodes << ", dofs " << e.dofs << ", quadrature points " << e.points;
  if (e.neighbors > 0.0) out << ", neighbours a point " << e.neighbors;
  out << "\n  matrix nonzeros " << e.nonzeros << ", factor nonzeros " << e.factor_nonzeros;
  if (e.grid_points > 0.0) out << ", Enrichment Grid points " << e.grid_points;
  out << "\n  output " << e.output_mb_per_step << " MB a written step, " << e.output_mb << " MB in all\n"
      << "  peak memory " << e.memory_mb << " MB (available now: " << available_memory_mb() << " MB)\n";
  if (e.ranks > 1) out << "  on " << e.ranks << " MPI ranks: " << e.memory_mb_per_rank << " MB the largest rank\n";
  return out.str();
}

nlohmann::ordered_json estimate_to_json(const ResourceEstimate& e) {
  return {{"size_key", e.size_key},  {"size", e.size},        {"mesh_cells", e.mesh_cells},
          {"mesh_nodes", e.mesh_nodes}, {"nodes", e.nodes},   {"dofs", e.dofs},
          {"points", e.points},      {"neighbors", e.neighbors}, {"nonzeros", e.nonzeros},
          {"factor_nonzeros", e.factor_nonzeros}, {"grid_points", e.grid_points},
          {"output_mb_per_step", e.output_mb_per_step}, {"output_mb", e.output_mb}, {"memory_mb", e.memory_mb},
          {"ranks", e.ranks}, {"memory_mb_per_rank", e.memory_mb_per_rank}};
}

double memory_limit_mb(const RankShare& ranks) {
  // This machine's memory shared by the ranks it runs (Open MPI says how many).
  const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
  const int here = local ? std::max(1, std::atoi(local)) : ranks.count;
  double limit = available_memory_mb() / std::max(1, here);
  // A user's own cap on each process (a shared machine, a batch job's share).
  if (const char* cap = std::getenv("KERF_MEMORY_LIMIT_MB")) {
    char* end = nullptr;
    const double mb = std::strtod(cap, &end);
    KERF_CHECK(end != cap && *end == '\0' && mb > 0.0, "environment variable KERF_MEMORY_LIMIT_MB: value '", cap,
               "' is not a number of megabytes; expected a positive number");
    limit = limit > 0.0 ? std::min(limit, mb) : mb;
  }
  return limit;
}

double available_memory_mb() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0.0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb / 1024.0;
  return 0.0;  // unknown: nothing is refused
}

void refuse_output_that_cannot_fit(const Scene& scene, const ResourceEstimate& e, const std::string& directory) {
  std::error_code failed;
  const double free_mb = static_cast<double>(std::filesystem::space(directory, failed).available) / 1048576.0;
  if (failed || e.output_mb <= free_mb) return;
  std::ostringstream why;
  why.precision(3);
  why << scene.locate("output.vtk").describe() << ": the ParaView series would take about " << e.output_mb
      << " MB (" << e.output_mb_per_step << " MB a written step); the disk holding " << directory << " has "
      << free_mb << " MB free; expected a larger output.vtk.every, vtk: false, or --force to run anyway";
  throw Error(why.str());
}

void refuse_what_cannot_fit(const Scene& scene, const ResourceEstimate& e, double limit_mb) {
  if (e.size_key.empty() || limit_mb <= 0.0 || e.memory_mb_per_rank <= limit_mb) return;
  std::ostringstream why;
  why.precision(3);
  why << scene.locate(e.size_key).describe() << ": value " << e.size << " asks for about " << e.nodes << " nodes and "
      << e.mesh_cells << " mesh cells, an estimated " << e.memory_mb_per_rank << " MB of memory"
      << (e.ranks > 1 ? " on the largest of " + std::to_string(e.ranks) + " MPI ranks" : std::string())
      << "; the limit is " << limit_mb
      << " MB a process (the memory available to it, or KERF_MEMORY_LIMIT_MB); expected a larger " << e.size_key
      << " (memory grows as its inverse " << (scene.dimension == 3 ? "cube" : "square") << "), "
      << (e.ranks > 1 ? "more ranks, " : "") << "or --force to run anyway";
  throw Error(why.str());
}

}  // namespace kerf
