// Cut-update benchmark (Google Benchmark): a blade sweeps through the 10 cm
// nodal block of bench_meshless.cpp (~5800 nodes): a vertical edge from
// z = 3 cm to above the top, moving along x at y = 5.03 cm (between node
// planes), one strip triangle per time. Each iteration adds one triangle and
// times the body's update: the Enrichment Grid rebuilt in the cut's common
// frame, the nodes whose weight changed found, their shape functions and
// stabilisation pairs recomputed. Arguments: the grid lookup (0 exact,
// 1 interpolated), the lattice spacing in tenths of the node spacing.
//   build/tests/kerf_benchmarks --benchmark_filter=CutUpdate
#include <benchmark/benchmark.h>

#include <algorithm>
#include <sstream>
#include <vector>

#include "core/timer.h"
#include "discretization/body_factory.h"
#include "problem/scene_reader.h"

namespace kerf {
namespace {

constexpr double node_spacing = 0.00588;
constexpr int blade_positions = 23;

Scene cut_block(bool interpolated, double grid_spacing) {
  std::ostringstream strip, times;
  for (int k = 0; k < blade_positions; ++k) {
    const double x = -0.005 + 0.005 * k;
    strip << (k ? ", " : "") << "[" << x << ", 0.0503, 0.03], [" << x << ", 0.0503, 0.11]";
    times << (k ? ", " : "") << std::max(0, 2 * k - 1) << ", " << 2 * k;
  }
  std::ostringstream yaml;
  yaml << R"(
name: cut_block
domain: {box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}
material: {young: 3000, poisson: 0.3, density: 1000}
discretization: {method: nodal, meshless: {spacing: )"
       << node_spacing << R"(, support: 2.3}}
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
  const Scene scene = cut_block(state.range(0) != 0, 0.1 * state.range(1) * node_spacing);
  RunReport report;
  std::unique_ptr<DiscreteBody> body;
  int next = 0;
  const int last = 2 * blade_positions - 2;  // time of the last triangle
  std::vector<double> seconds;
  double nodes = 0.0, points = 0.0;
  for (auto _ : state) {
    if (!body || next > last) {
      state.PauseTiming();
      body = make_body(scene, report);
      next = 1;  // the first triangle is present at t = 0
      state.ResumeTiming();
    }
    const double start = now_seconds();
    const std::optional<CutUpdate> update = body->advance_cuts(next++);
    seconds.push_back(now_seconds() - start);
    if (update) nodes += update->nodes, points += update->points;
  }
  std::sort(seconds.begin(), seconds.end());
  state.counters["median_update_ms"] = 1e3 * seconds[seconds.size() / 2];
  state.counters["max_update_ms"] = 1e3 * seconds.back();
  state.counters["nodes_changed_mean"] = nodes / seconds.size();
  state.counters["points_updated_mean"] = points / seconds.size();
  state.counters["nodes"] = body->node_count();
}

BENCHMARK(BM_CutUpdate)->Args({0, 5})->Args({1, 5})->Args({0, 10})->Args({1, 10})->Iterations(88)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace kerf
