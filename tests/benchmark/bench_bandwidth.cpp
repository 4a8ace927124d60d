// This machine's memory bandwidth, the floor under every pass that streams a
// table: a STREAM-style triad a = b + s c over both cores (the threads kerf's
// kernels use), counted as STREAM does (three arrays of doubles a pass, no
// write-allocate). Two sizes: arrays of 3 x 128 MB (main memory) and of
// 3 x 6 MB (about what a hot path's tables hold: resident in the 32 MB L3 of
// this VM), so a path's bytes per step can be read as a time either way.
//   build/tests/kerf_benchmarks --benchmark_filter=Triad
#include <benchmark/benchmark.h>

#include <cstddef>
#include <memory>

#include "floor_report.h"

namespace kerf::bench {
namespace {

/// Argument: megabytes per array.
void BM_Triad(benchmark::State& state) {
  const std::ptrdiff_t n = (state.range(0) << 20) / static_cast<std::ptrdiff_t>(sizeof(double));
  std::unique_ptr<double[]> a(new double[n]), b(new double[n]), c(new double[n]);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i) a[i] = 0.0, b[i] = 1.0, c[i] = 2.0;  // first touch by the thread that streams it
  const double s = 3.0;
  for (auto _ : state) {
    double* pa = a.get();
    const double *pb = b.get(), *pc = c.get();
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
    benchmark::ClobberMemory();
  }
  const double bytes = 3.0 * sizeof(double) * static_cast<double>(n);
  state.counters["bytes_per_second"] = benchmark::Counter(bytes, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["array_mb"] = static_cast<double>(n) * sizeof(double) / (1 << 20);
}

BENCHMARK(BM_Triad)->Arg(128)->Arg(6)->UseRealTime()->Unit(benchmark::kMicrosecond);

const bool registered = (use_bandwidth_of("BM_Triad/128", "memory"), use_bandwidth_of("BM_Triad/6", "L3"), true);

}  // namespace
}  // namespace kerf::bench
