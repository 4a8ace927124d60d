// What the benchmark library itself costs an iteration. Debian builds
// libbenchmark without NDEBUG, so every run warns "Library was built as
// DEBUG": its own checks stay on in the timing loop. This empty loop measures
// them (nanoseconds an iteration, against the milliseconds of every hot path
// timed here), and a pause/resume pair, which the cut benchmarks use.
//   build/tests/kerf_benchmarks --benchmark_filter=LibraryOverhead
#include <benchmark/benchmark.h>

namespace kerf::bench {
namespace {

void BM_LibraryOverheadEmptyIteration(benchmark::State& state) {
  for (auto _ : state) benchmark::ClobberMemory();
}

void BM_LibraryOverheadPauseResume(benchmark::State& state) {
  for (auto _ : state) {
    state.PauseTiming();
    state.ResumeTiming();
  }
}

BENCHMARK(BM_LibraryOverheadEmptyIteration)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_LibraryOverheadPauseResume)->Unit(benchmark::kNanosecond);

}  // namespace
}  // namespace kerf::bench
