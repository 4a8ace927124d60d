// One MLS row (values and gradients, linear basis, 3D) by the general kernel
// (mls_shape.h: eigen-decomposition, 104-byte weights) and by the linear one
// (mls_linear.h: Cholesky, Jacobi eigenvalues for the condition number), at
// 400 points of a jittered lattice with supports of 2.3 spacings (about 50
// nodes a point, as in the nodal block), one thread. Each iteration is 400 rows.
//   build/tests/kerf_benchmarks --benchmark_filter=MlsRow
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "discretization/meshless/mls_linear.h"

namespace kerf {
namespace {

struct Rows {
  std::vector<Vec3> point;
  std::vector<std::vector<Vec3>> near;
  std::vector<std::vector<WeightValue>> weights;
  std::vector<std::vector<WeightWithGradient>> lean;
  double support = 0.0;
};

Rows lattice_rows() {
  constexpr double h = 0.01;
  Rows r;
  r.support = 2.3 * h;
  std::mt19937 random(3);
  std::uniform_real_distribution<double> jitter(-0.2 * h, 0.2 * h), inside(0.3, 0.7);
  std::vector<Vec3> nodes;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j)
      for (int k = 0; k <= 10; ++k)
        nodes.emplace_back(i * h + jitter(random), j * h + jitter(random), k * h + jitter(random));
  for (int p = 0; p < 400; ++p) {
    const Vec3 x(0.1 * inside(random), 0.1 * inside(random), 0.1 * inside(random));
    r.point.push_back(x);
    r.near.emplace_back(), r.weights.emplace_back(), r.lean.emplace_back();
    for (const Vec3& y : nodes)
      if ((x - y).norm() < r.support) {
        r.near.back().push_back(y);
        r.weights.back().push_back(quartic_weight(x, y, r.support, false));
        r.lean.back().push_back(quartic_weight_with_gradient(x, y, r.support));
      }
  }
  return r;
}

void BM_MlsRowGeneral(benchmark::State& state) {
  const Rows r = lattice_rows();
  MlsShape out;
  for (auto _ : state)
    for (std::size_t p = 0; p < r.point.size(); ++p) {
      mls_shape_functions(3, MlsBasis::linear, r.point[p], r.near[p], r.weights[p], r.support, false, out);
      benchmark::DoNotOptimize(out.value.data());
    }
  state.counters["rows"] = static_cast<double>(r.point.size());  // time / rows: one row
}

void BM_MlsRowLinear(benchmark::State& state) {
  const Rows r = lattice_rows();
  MlsShape out;
  for (auto _ : state)
    for (std::size_t p = 0; p < r.point.size(); ++p) {
      mls_linear_shape_functions(3, r.point[p], r.near[p], r.lean[p], r.support, out);
      benchmark::DoNotOptimize(out.value.data());
    }
  state.counters["rows"] = static_cast<double>(r.point.size());  // time / rows: one row
}

BENCHMARK(BM_MlsRowGeneral)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MlsRowLinear)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace kerf
