// Cut-update benchmark (Google Benchmark): a blade sweeps through the 10 cm
// nodal block of bench_meshless.cpp (~5800 nodes): a vertical edge from
// z = 3 cm to above the top, moving along x at y = 5.03 cm (between node
// planes), one strip triangle per time. Each iteration adds one triangle and
// times the body's update: the Enrichment Grid rebuilt in the cut's common
// frame, the nodes whose weight changed found, their shape functions and
// stabilisation pairs recomputed, and (meshless.cut_cells: split) the cells
// the new piece crosses split and the points of the cells at the cut built
// again. Arguments: the grid lookup (0 exact, 1 interpolated), the lattice
// spacing in tenths of the node spacing, cut_cells split (1) or whole (0).
// FemRemeshUpdate times the `fem: remesh` baseline of the same update on the
// matching tet4 mesh (element size = node spacing): gmsh meshes the block with
// the strip so far embedded and opens it (Crack plugin), the FEM body is
// built, and the displacement is carried to the new nodes by interpolation
// in the old mesh.
//   build/tests/kerf_benchmarks --benchmark_filter='CutUpdate|FemRemeshUpdate'

#include <benchmark/benchmark.h>

#include <algorithm>
#include <sstream>
#include <vector>

#include "core/timer.h"
#include "discretization/body_capabilities.h"
#include "discretization/body_factory.h"
#include "discretization/meshless/nodal_body.h"
#include "floor_report.h"
#include "mls_rows_floor.h"
#include "problem/scene_reader.h"

namespace kerf {
namespace {

constexpr double node_spacing = 0.00588;
constexpr int blade_positions = 23;

/// The block and its blade; with `triangles` > 0, FEM (tet4) with the first
/// `triangles` of the strip present from the start.
Scene cut_block(bool interpolated, double grid_spacing, int triangles = 0, bool split_cells = true) {
  std::ostringstream strip, times;
  const int vertices = triangles > 0 ? triangles + 2 : 2 * blade_positions;
  for (int v = 0; v < vertices; ++v) {
    const int k = v / 2;  // blade position
    const double x = -0.005 + 0.005 * k;
    strip << (v ? ", " : "") << "[" << x << ", 0.0503, " << (v % 2 ? 0.11 : 0.03) << "]";
    const int appears = v % 2 ? 2 * k : std::max(0, 2 * k - 1);
    times << (v ? ", " : "") << (triangles > 0 ? 0 : appears);  // FEM: every piece there from the start
  }
  std::ostringstream yaml;
  yaml << R"(
name: cut_block
domain: {box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}
material: {young: 3000, poisson: 0.3, density: 1000}
discretization: {method: )"
       << (triangles > 0 ? "fem" : "nodal") << ", fem: {element: tet4, size: " << node_spacing
       << "}, meshless: {spacing: " << node_spacing << ", cut_cells: " << (split_cells ? "split" : "whole")
       << R"(, support: 2.3}}
boundary:
  - select: {plane: {axis: z, at: 0.0}}
    fix: [x, y, z]
body_force: {gravity: [0, 0, -9.81]}
cuts:
  - strip: [)" << strip.str() << R"(]
    times: [)" << times.str() << R"(]
    enrichment: grid
    grid: {spacing: )" << grid_spacing << ", lookup: " << (interpolated ? "interpolated" : "exact") << R"(}
solve: {dt: 0.001, duration: 10.0}
output: {vtk: false}
)";
  return parse_scene(yaml.str(), "benchmark", ".");
}

void BM_CutUpdate(benchmark::State& state) {
  const Scene scene = cut_block(state.range(0) != 0, 0.1 * state.range(1) * node_spacing, 0, state.range(2) != 0);
  RunReport report;
  std::unique_ptr<DiscreteBody> body;
  CutsInShapeFunctions* cuts = nullptr;
  int next = 0;
  const int last = 2 * blade_positions - 2;  // time of the last triangle
  std::vector<double> seconds;
  double nodes = 0.0, points = 0.0;
  for (auto _ : state) {
    if (!body || next > last) {
      state.PauseTiming();
      body = make_body(scene, report);
      cuts = capability<CutsInShapeFunctions>(*body);
      next = 1;  // the first triangle is present at t = 0
      state.ResumeTiming();
    }
    const double start = now_seconds();
    const CutUpdate update = cuts->update_for_cuts(next++);
    seconds.push_back(now_seconds() - start);
    nodes += update.nodes, points += update.points;
  }
  std::sort(seconds.begin(), seconds.end());
  state.counters["median_update_ms"] = 1e3 * seconds[seconds.size() / 2];
  state.counters["max_update_ms"] = 1e3 * seconds.back();
  state.counters["nodes_changed_mean"] = nodes / seconds.size();
  state.counters["points_updated_mean"] = points / seconds.size();
  state.counters["nodes"] = body->node_count();
}

// The floor of one update (mls_rows_floor.h): the MLS rows of as many nodes
// as an interpolated update recomputes (436 a piece, measured), the nodes
// nearest the blade's front at mid-sweep, with the table's cut factors.
void BM_CutUpdateFloor(benchmark::State& state) {
  const Scene scene = cut_block(true, 0.5 * node_spacing);
  RunReport report;
  auto body = make_body(scene, report);
  const auto& nodal = dynamic_cast<const NodalBody&>(*body);
  const ShapeTable& table = nodal.domain().at_nodes();
  const NodeSet& nodes = nodal.domain().nodes();
  std::vector<Index> rows(nodes.size());
  for (Index n = 0; n < nodes.size(); ++n) rows[n] = n;
  const Vec3 front(0.05, 0.0503, 0.07);
  const std::size_t count = static_cast<std::size_t>(state.range(0));
  std::partial_sort(rows.begin(), rows.begin() + count, rows.end(), [&](Index a, Index b) {
    return (nodes.positions[a] - front).norm() < (nodes.positions[b] - front).norm();
  });
  rows.resize(count);
  std::vector<double> factor = table.weight_factor;
  factor.resize(table.neighbours.index.size(), 1.0);
  const bench::MlsRowsFloorData data{table.neighbours.start, table.neighbours.index, nodes.positions,
                                     nodes.positions, nodes.support, factor};
  std::vector<double> value(table.value.size()), gradient(table.gradient.size());
  for (auto _ : state) bench::mls_rows_floor(data, rows, value, gradient);
  benchmark::DoNotOptimize(value.data());
  state.counters["rows"] = static_cast<double>(count);
}

void BM_FemRemeshUpdate(benchmark::State& state) {
  RunReport report;
  const int last = 2 * blade_positions - 2;
  std::unique_ptr<DiscreteBody> body = make_body(cut_block(false, node_spacing, 1), report);
  int next = 2;
  std::vector<double> remesh, map;
  for (auto _ : state) {
    if (next > last) next = 2;
    state.PauseTiming();
    const Scene scene = cut_block(false, node_spacing, next++);
    Vector u = Vector::Zero(body->dof_count());  // a displacement to carry over: a shear along x
    for (Index n = 0; n < body->node_count(); ++n) u[3 * n] = 1e-3 * body->node_position(n).z();
    state.ResumeTiming();
    const double start = now_seconds();
    std::unique_ptr<DiscreteBody> next_body = make_body(scene, report);
    const double meshed = now_seconds();
    Vector mapped = Vector::Zero(next_body->dof_count());
    for (Index n = 0; n < next_body->node_count(); ++n) {
      const std::optional<PointInterpolation> at = body->interpolation_at(next_body->node_position(n));
      if (!at) continue;
      for (std::size_t k = 0; k < at->nodes.size(); ++k)
        for (int c = 0; c < 3; ++c) mapped[3 * n + c] += at->weights[k] * u[3 * at->nodes[k] + c];
    }
    const double done = now_seconds();
    benchmark::DoNotOptimize(mapped.data());
    remesh.push_back(meshed - start);
    map.push_back(done - meshed);
    body = std::move(next_body);
  }
  std::sort(remesh.begin(), remesh.end());
  std::sort(map.begin(), map.end());
  state.counters["median_remesh_ms"] = 1e3 * remesh[remesh.size() / 2];
  state.counters["median_map_ms"] = 1e3 * map[map.size() / 2];
  state.counters["nodes"] = body->node_count();
  state.counters["cells"] = body->element_count();
}

BENCHMARK(BM_FemRemeshUpdate)->Iterations(44)->Repetitions(1)->Unit(benchmark::kMillisecond);  // 44 remeshes: about a minute

// The third argument: meshless.cut_cells split (1, the default) or whole (0, the paper's).
BENCHMARK(BM_CutUpdate)
    ->Args({0, 5, 1})
    ->Args({1, 5, 1})
    ->Args({0, 10, 1})
    ->Args({1, 10, 1})
    ->Args({0, 5, 0})
    ->Args({1, 5, 0})
    ->Iterations(88)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CutUpdateFloor)->Arg(436)->Unit(benchmark::kMillisecond);

constexpr const char* rows_alone = "the linear MLS rows alone (mls_linear.h) for the rows an update recomputes";
// Whole cells, the default for a growing cut (issue 40's figure); the names
// carry all three arguments, or the report finds no run to pair.
const bool paired = (bench::pair_with_floor("BM_CutUpdate/1/5/0", "BM_CutUpdateFloor/436", rows_alone),
                     bench::pair_with_floor("BM_CutUpdate/0/5/0", "BM_CutUpdateFloor/436", rows_alone), true);

}  // namespace
}  // namespace kerf
