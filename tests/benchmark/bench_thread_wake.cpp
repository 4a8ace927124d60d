// What waking kerf's threads costs: one parallel region that does nothing,
// under kerf's thread policy (passive waiting: the other thread sleeps between
// regions), and a gather of 256 values (half an item of the restriction to
// the free dofs in core/threads_worth_waking.h's units). The threshold there
// is read against these.
//   build/tests/kerf_benchmarks --benchmark_filter=ThreadWake
#include <benchmark/benchmark.h>
#include <omp.h>

#include <vector>

namespace kerf::bench {
namespace {

void BM_ThreadWakeEmptyParallelRegion(benchmark::State& state) {
  for (auto _ : state) {
#pragma omp parallel
    {
      int thread = omp_get_thread_num();
      benchmark::DoNotOptimize(thread);
    }
  }
  state.counters["threads"] = omp_get_max_threads();
}

void BM_ThreadWakeGather256Values(benchmark::State& state) {
  std::vector<double> from(1 << 16, 1.0), to(256);
  std::vector<int> at(256);
  for (int i = 0; i < 256; ++i) at[i] = (i * 7919) % (1 << 16);
  for (auto _ : state) {
    for (int i = 0; i < 256; ++i) to[i] = 2.0 * from[at[i]];
    benchmark::DoNotOptimize(to.data());
  }
}

BENCHMARK(BM_ThreadWakeEmptyParallelRegion)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ThreadWakeGather256Values)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace kerf::bench
