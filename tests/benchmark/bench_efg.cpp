// EFG's stiffness (Google Benchmark): K on the cantilever's box (10 x 2 x 2 cm)
// at 2.5 mm, the size issue 40 compares with tet10 (181k Gauss points of the
// symmetric rule, about 39 neighbours each), written node by node into the
// matrix (add_tangent_into, what the solvers call) or cell by cell through a
// sink (tangent, what it did before), for a linear law (one tangent: the
// moments path) and the neo-Hookean one. The floor: the same point pairs'
// arithmetic alone, each point's pairs summed into a buffer of its own (no
// lookups, no gathering by node).
//   build/tests/kerf_benchmarks --benchmark_filter=EfgStiffness
#include <benchmark/benchmark.h>

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>

#include "discretization/body_factory.h"
#include "discretization/meshless/efg_body.h"
#include "floor_report.h"
#include "problem/scene_reader.h"
#include "solvers/sparse_assembly.h"

namespace kerf {
namespace {

/// The body, its pattern and a displacement with strains of about 1%.
struct EfgFixture {
  std::unique_ptr<DiscreteBody> body;
  SparseMatrix pattern;
  Vector u;
};

/// Law 0: linear; 1: neo-Hookean.
const EfgFixture& fixture(std::int64_t law) {
  static std::map<std::int64_t, EfgFixture> built;
  auto found = built.find(law);
  if (found != built.end()) return found->second;
  const std::string yaml = R"(
name: efg_cantilever
domain: {box: {min: [0, 0, 0], max: [0.1, 0.02, 0.02]}}
material: {young: 1.0e6, poisson: 0.3, density: 1000.0}
discretization: {method: efg, meshless: {spacing: 0.0025, quadrature: {rule: symmetric}}}
boundary:
  - select: {plane: {axis: x, at: 0.0}}
    fix: [x, y, z]
body_force: {gravity: [0, 0, -9.81]}
solve: {analysis: static}
output: {vtk: false}
)";
  const Scene scene =
      parse_scene(yaml, "benchmark", ".", {std::string("material.model=") + (law == 0 ? "linear" : "neohookean")});
  RunReport report;
  EfgFixture f;
  f.body = make_body(scene, report);
  f.pattern = build_pattern(*f.body);
  f.u = Vector::Zero(f.body->dof_count());
  for (Index n = 0; n < f.body->node_count(); ++n) f.u[3 * n + 2] = -0.01 * f.body->node_position(n).x();
  return built.emplace(law, std::move(f)).first->second;
}

/// Path 0: cell blocks through a sink; 1: node by node into the matrix. Law as fixture's.
void BM_EfgStiffness(benchmark::State& state) {
  const EfgFixture& f = fixture(state.range(1));
  const auto& efg = dynamic_cast<const EfgBody&>(*f.body);
  SparseMatrix K = f.pattern;
  for (auto _ : state) {
    std::fill(K.valuePtr(), K.valuePtr() + K.nonZeros(), 0.0);
    if (state.range(0) == 1)
      efg.add_tangent_into(f.u, csr_view(K), nullptr);
    else
      efg.tangent(f.u, add_into(K, 1.0, 3), nullptr);
    benchmark::DoNotOptimize(K.valuePtr());
  }
  state.counters["points"] = static_cast<double>(efg.points().point_count());
}

#pragma GCC diagnostic ignored "-Wpsabi"  // vectors never cross a call: everything below is inlined
typedef double v4d __attribute__((vector_size(32)));

/// Every point's pairs (a <= b of its neighbours): with one tangent the
/// moments w g_a g_b^T (3 lanes x 3), else w g_a^T D g_b (D the one
/// tangent, read as a point's would be), summed into the point's own buffer.
template <bool Moments>
__attribute__((target("avx2,fma"))) double pairs_alone(const ShapeTable& t, std::span<const double> weights,
                                                       const Mat9& D) {
  const Index slots = static_cast<Index>(t.neighbours.index.size());
  double total = 0.0;
#pragma omp parallel reduction(+ : total)
  {
    std::vector<double> storage(4 * 3 * 64 * 64 + 4);  // 64 x 64 blocks of 3 vectors, 32-byte aligned
    const std::size_t misaligned = reinterpret_cast<std::uintptr_t>(storage.data()) % 32;
    v4d* buffer = reinterpret_cast<v4d*>(storage.data() + (misaligned ? (32 - misaligned) / sizeof(double) : 0));
#pragma omp for schedule(dynamic, 256)
    for (Index p = 0; p < t.point_count(); ++p) {
      const Index s0 = t.neighbours.start[p], n = t.neighbours.start[p + 1] - s0;
      const double w = weights[p];
      for (Index a = 0; a < n; ++a) {
        const double* ga = t.gradient.data() + 3 * (s0 + a);
        v4d S[3][3];
        if constexpr (!Moments)
          for (int i = 0; i < 3; ++i)
            for (int l = 0; l < 3; ++l)
              for (int c = 0; c < 3; ++c) {
                double sum = 0.0;
                for (int j = 0; j < 3; ++j) sum += ga[j] * D(i + 3 * j, c + 3 * l);
                S[i][l][c] = w * sum;
              }
        for (Index b = a; b < n; ++b) {
          v4d gb = {0.0, 0.0, 0.0, 0.0};
          if (s0 + b + 1 < slots)
            std::memcpy(&gb, t.gradient.data() + 3 * (s0 + b), sizeof gb);
          else
            std::memcpy(&gb, t.gradient.data() + 3 * (s0 + b), 3 * sizeof(double));
          v4d* block = buffer + 3 * (64 * (a % 64) + b % 64);
          for (int i = 0; i < 3; ++i)
            block[i] += Moments ? (w * ga[i]) * gb : S[i][0] * gb[0] + S[i][1] * gb[1] + S[i][2] * gb[2];
        }
      }
      total += buffer[0][0];
    }
  }
  return total;
}

/// The floor of BM_EfgStiffness/1/law: the pairs' arithmetic alone.
void BM_EfgStiffnessFloor(benchmark::State& state) {
  const EfgFixture& f = fixture(state.range(0));
  const auto& efg = dynamic_cast<const EfgBody&>(*f.body);
  Mat3 P;
  Mat9 D;
  MaterialLaw(MaterialModel::neohookean, 1.0e6, 0.3).stress_and_tangent(Mat3::Identity(), P, D);
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) {
    state.SkipWithError("the floor is written for AVX2 + FMA");
    return;
  }
  for (auto _ : state) {
    const double total = state.range(0) == 0 ? pairs_alone<true>(efg.points().shapes(), efg.points().weights(), D)
                                             : pairs_alone<false>(efg.points().shapes(), efg.points().weights(), D);
    benchmark::DoNotOptimize(total);
  }
}

BENCHMARK(BM_EfgStiffness)->Args({1, 0})->Args({0, 0})->Args({1, 1})->Args({0, 1})->Iterations(5)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EfgStiffnessFloor)->Arg(0)->Arg(1)->Iterations(5)->Unit(benchmark::kMillisecond);

const bool paired = (bench::pair_with_floor("BM_EfgStiffness/1/0", "BM_EfgStiffnessFloor/0",
                                            "the moments of every point's pairs, alone"),
                     bench::pair_with_floor("BM_EfgStiffness/1/1", "BM_EfgStiffnessFloor/1",
                                            "every point's pairs through its tangent, alone"),
                     bench::pair_with_floor("BM_EfgStiffness/0/0", "BM_EfgStiffnessFloor/0",
                                            "the cells through a sink, against the moments alone"),
                     true);

}  // namespace
}  // namespace kerf
