// Meshless benchmarks (Google Benchmark): the explicit central-difference step
// of nodal integration on a 10 cm block of ~5800 lattice nodes with ~40
// neighbours each (the paper's meshless method took 20.11 ms a step; a 1 kHz
// haptic loop needs < 1 ms), its setup (nodes, volumes, neighbours, shape
// functions) and the memory it holds per node.
//   build/tests/kerf_benchmarks --benchmark_filter=Nodal
#include <benchmark/benchmark.h>

#include <algorithm>
#include <malloc.h>
#include <vector>

#include "core/timer.h"
#include "discretization/body_factory.h"
#include "problem/scene_reader.h"
#include "solvers/stepper.h"

namespace kerf {
namespace {

Scene nodal_block(bool stabilization, const std::string& material) {
  std::string yaml = R"(
name: nodal_block
domain: {box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}
material: {young: 3000, poisson: 0.3, density: 1000}
discretization: {method: nodal, meshless: {spacing: 0.00588, support: 2.3}}
boundary:
  - select: {plane: {axis: z, at: 0.0}}
    fix: [x, y, z]
body_force: {gravity: [0, 0, -9.81]}
solve: {dt: 0.001, duration: 10.0}
output: {vtk: false}
)";
  return parse_scene(yaml, "benchmark", ".",
                     {std::string("discretization.meshless.stabilization=") + (stabilization ? "true" : "false"),
                      "material.model=" + material});
}

/// Bytes of heap in use (glibc's allocator: small blocks plus mmapped ones).
double heap_bytes() {
  struct mallinfo2 info = mallinfo2();
  return static_cast<double>(info.uordblks + info.hblkhd);
}

void BM_NodalExplicitStep(benchmark::State& state) {
  // Arguments: stabilisation on (1) or off (0); linear (0) or corotational (1) material.
  Scene scene = nodal_block(state.range(0) != 0, state.range(1) ? "corotational" : "linear");
  RunReport report;
  auto body = make_body(scene, report);
  MechanicalSystem mechanics(*body, scene, report);
  auto stepper = make_stepper(mechanics, scene, report);
  SolverState s;
  stepper->initialize(s);
  std::vector<double> steps;
  for (auto _ : state) {
    const double start = now_seconds();
    stepper->advance(s, scene.solve.dt);
    steps.push_back(now_seconds() - start);
  }
  std::sort(steps.begin(), steps.end());
  state.counters["median_step_ms"] = 1e3 * steps[steps.size() / 2];
  state.counters["nodes"] = body->node_count();
  state.counters["neighbors_mean"] = body->mean_neighbors();
  state.counters["critical_dt_ms"] = 1e3 * report.solver.critical_dt_s.value();
}

// Setup of the body alone: lattice, Delaunay volumes, k-d tree, neighbour
// lists, MLS shape functions and gradients, stabilisation pair weights.
void BM_NodalSetup(benchmark::State& state) {
  Scene scene = nodal_block(true, "corotational");
  double bytes_per_node = 0.0;
  Index nodes = 0;
  for (auto _ : state) {
    RunReport report;
    const double before = heap_bytes();
    auto body = make_body(scene, report);
    bytes_per_node = (heap_bytes() - before) / body->node_count();
    nodes = body->node_count();
  }
  state.counters["nodes"] = nodes;
  state.counters["heap_bytes_per_node"] = bytes_per_node;
}

BENCHMARK(BM_NodalExplicitStep)->Args({1, 0})->Args({0, 0})->Args({1, 1})->Args({0, 1})->Iterations(2000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NodalSetup)->Iterations(3)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace kerf
