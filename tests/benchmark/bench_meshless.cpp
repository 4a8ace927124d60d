// Meshless benchmarks (Google Benchmark): the explicit central-difference step
// of nodal integration on a 10 cm block of ~5800 lattice nodes with ~40
// neighbours each (the paper's meshless method took 20.11 ms a step; a 1 kHz
// haptic loop needs < 1 ms), its setup (nodes, volumes, neighbours, shape
// functions) and the memory it holds per node.
//   build/tests/kerf_benchmarks --benchmark_filter=Nodal
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <malloc.h>
#include <vector>

#include "core/timer.h"
#include "discretization/body_factory.h"
#include "discretization/meshless/nodal_body.h"
#include "problem/material.h"
#include "floor_report.h"
#include "nodal_floor.h"
#include "problem/scene_reader.h"
#include "solvers/stepper.h"

namespace kerf {
namespace {

/// meshless.stabilization by a benchmark argument: 0 none, 1 the hourglass term, 2 NSNI.
const char* stabilization_name(std::int64_t argument) {
  static constexpr const char* names[] = {"none", "hourglass", "nsni"};
  return names[argument];
}

Scene nodal_block(const std::string& stabilization, const std::string& material) {
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
                     {"discretization.meshless.stabilization=" + stabilization,
                      "material.model=" + material});
}

/// Bytes of heap in use (glibc's allocator: small blocks plus mmapped ones).
double heap_bytes() {
  struct mallinfo2 info = mallinfo2();
  return static_cast<double>(info.uordblks + info.hblkhd);
}

void BM_NodalExplicitStep(benchmark::State& state) {
  // Arguments: stabilisation (stabilization_name); linear (0) or corotational (1) material.
  Scene scene = nodal_block(stabilization_name(state.range(0)), state.range(1) ? "corotational" : "linear");
  RunReport report;
  auto body = make_body(scene, report);
  MechanicalSystem mechanics(*body, scene, report);
  auto stepper = make_stepper(mechanics, stepper_settings(scene), report);
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
  state.counters["bytes_per_step"] = static_cast<double>(dynamic_cast<const NodalBody&>(*body).force_pass_bytes());
}

// The floor of the step above (nodal_floor.h) on the same body's tables, plus
// the central-difference update it needs (v += dt M^-1 (f_ext - f_int), u += dt v),
// on vectors 4 to a node. Argument: stabilisation on (1) or off (0).
void BM_NodalStepFloor(benchmark::State& state) {
  if (!bench::nodal_floor_supported()) return state.SkipWithError("the floor needs AVX2 and FMA");
  const bool stabilized = state.range(0) != 0;
  Scene scene = nodal_block(stabilized ? "hourglass" : "none", "linear");
  RunReport report;
  auto body = make_body(scene, report);
  const auto& nodal = dynamic_cast<const NodalBody&>(*body);
  const ShapeTable& table = nodal.domain().at_nodes();
  const NodeSet& nodes = nodal.domain().nodes();
  const Lame lame = Lame::from_young_poisson(scene.material.young, scene.material.poisson);
  // Any positive k costs the same; this one has the stabilisation's scale.
  std::vector<double> stiffness(table.neighbours.index.size(), 0.1 * lame.mu * nodes.volume[0] / 1e-4);
  const std::vector<double> positions = padded_positions(nodes.positions);
  bench::NodalFloorData data{table.neighbours.start, table.neighbours.index, table.gradient, stiffness,
                             aligned_32(positions), nodes.volume, lame.lambda, lame.mu};
  const Index N = body->node_count();
  const Vector mass = body->lumped_mass();
  Vector load;
  body->external_force(0.0, load);
  std::vector<double> m4(4 * N + 4, 1.0), load4(4 * N + 4, 0.0), u(4 * N + 4, 0.0), v(4 * N + 4, 0.0),
      f(4 * N + 4, 0.0), scratch;
  for (Index n = 0; n < N; ++n)
    for (int i = 0; i < 3; ++i) m4[4 * n + i] = mass[3 * n + i], load4[4 * n + i] = load[3 * n + i];
  double* u4 = const_cast<double*>(aligned_32(u));
  double* f4 = const_cast<double*>(aligned_32(f));
  const double dt = scene.solve.dt;
  for (auto _ : state) {
    bench::nodal_floor_force(data, stabilized, u4, f4, scratch);
#pragma omp parallel for schedule(static)
    for (Index j = 0; j < 4 * N; ++j) {
      v[j] += dt * (load4[j] - f4[j]) / m4[j];
      u4[j] += dt * v[j];
    }
  }
  benchmark::DoNotOptimize(u4);
}

// Setup of the body alone: lattice, Delaunay volumes, k-d tree, neighbour
// lists, MLS shape functions and gradients, the stabilisation's tables (the
// hourglass pair weights, or NSNI's second derivatives and cell moments).
// Argument: the stabilisation (stabilization_name).
void BM_NodalSetup(benchmark::State& state) {
  Scene scene = nodal_block(stabilization_name(state.range(0)), "corotational");
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

BENCHMARK(BM_NodalExplicitStep)->Args({1, 0})->Args({0, 0})->Args({1, 1})->Args({0, 1})->Args({2, 0})->Args({2, 1})->Iterations(2000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NodalStepFloor)->Arg(1)->Arg(0)->Iterations(2000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NodalSetup)->Arg(1)->Arg(2)->Iterations(3)->Unit(benchmark::kMillisecond);

const bool paired = (bench::pair_with_floor("BM_NodalExplicitStep/1/0", "BM_NodalStepFloor/1",
                                            "bare linear stabilised pass on the same tables + update"),
                     bench::pair_with_floor("BM_NodalExplicitStep/0/0", "BM_NodalStepFloor/0",
                                            "bare linear pass on the same tables + update"),
                     bench::pair_with_floor("BM_NodalExplicitStep/1/1", "BM_NodalStepFloor/1",
                                            "bare LINEAR stabilised pass (no rotation) + update"),
                     bench::pair_with_floor("BM_NodalExplicitStep/0/1", "BM_NodalStepFloor/0",
                                            "bare LINEAR pass (no rotation) + update"),
                     // NSNI has no bare kernel of its own: its floor is its bytes over the
                     // triad's bandwidth (the bytes/memory column); the hourglass pass beside it.
                     bench::pair_with_floor("BM_NodalExplicitStep/2/0", "BM_NodalStepFloor/1",
                                            "the hourglass term's bare pass; NSNI's floor: bytes/memory"),
                     bench::pair_with_floor("BM_NodalExplicitStep/2/1", "BM_NodalStepFloor/1",
                                            "the hourglass term's bare LINEAR pass; NSNI's floor: bytes/memory"),
                     true);

}  // namespace
}  // namespace kerf
