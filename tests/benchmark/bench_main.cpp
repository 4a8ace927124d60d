// The benchmark binary's entry: the machine set up as kerf runs (OpenMP
// threads capped at the cores, denormals flushed), every benchmark repeated
// (5 times unless asked otherwise, medians reported), and each hot path
// printed beside its floor at the end (floor_report.h).
//   build/tests/kerf_benchmarks                      # everything, ~15 minutes
//   build/tests/kerf_benchmarks --benchmark_filter='Nodal|Triad'
#include <benchmark/benchmark.h>

#include <cstring>
#include <string>
#include <vector>

#include "core/denormals.h"
#include "core/thread_policy.h"
#include "floor_report.h"

namespace {

bool asked_for(int argc, char** argv, const char* flag) {
  for (int i = 1; i < argc; ++i)
    if (std::strncmp(argv[i], flag, std::strlen(flag)) == 0) return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  kerf::apply_thread_policy(argv);
  kerf::flush_denormals_to_zero();
  std::vector<std::string> defaults;
  if (!asked_for(argc, argv, "--benchmark_repetitions")) defaults.push_back("--benchmark_repetitions=5");
  if (!asked_for(argc, argv, "--benchmark_report_aggregates_only") &&
      !asked_for(argc, argv, "--benchmark_display_aggregates_only"))
    defaults.push_back("--benchmark_display_aggregates_only=true");
  std::vector<char*> args(argv, argv + argc);
  for (std::string& d : defaults) args.push_back(d.data());
  int count = static_cast<int>(args.size());
  args.push_back(nullptr);
  benchmark::Initialize(&count, args.data());
  if (benchmark::ReportUnrecognizedArguments(count, args.data())) return 1;
  kerf::bench::FloorReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
