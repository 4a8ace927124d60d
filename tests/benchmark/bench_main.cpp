// The benchmark binary's entry: the machine set up as kerf runs (OpenMP
// threads capped at the cores, denormals flushed), every benchmark repeated
// (5 times unless asked otherwise, medians reported), and each hot path
// printed beside its floor at the end (floor_report.h).
//   build/tests/kerf_benchmarks                      # everything, ~15 minutes
//   build/tests/kerf_benchmarks --benchmark_filter='Nodal|Triad'
#include <benchmark/benchmark.h>

#include <unistd.h>

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

/// The console's options as Google Benchmark takes them for a reporter of its
/// own (one passed in keeps its constructor's, colour even into a file):
/// colour on a terminal, unless --benchmark_color says otherwise.
benchmark::ConsoleReporter::OutputOptions console_options(int argc, char** argv) {
  bool color = isatty(STDOUT_FILENO);
  const std::string flag = "--benchmark_color=";
  for (int i = 1; i < argc; ++i)
    if (std::strncmp(argv[i], flag.c_str(), flag.size()) == 0) {
      const std::string value = argv[i] + flag.size();
      if (value != "auto") color = value == "true" || value == "yes" || value == "1";
    }
  using Options = benchmark::ConsoleReporter::OutputOptions;
  return static_cast<Options>(Options::OO_Tabular | (color ? Options::OO_Color : Options::OO_None));
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
  kerf::bench::FloorReporter reporter(console_options(argc, argv));
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
