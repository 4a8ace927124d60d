#pragma once
// Each hot path's benchmark is paired with its floor: a bare kernel doing the
// least work the path must do (same data, same arithmetic, no framework), run
// in the same binary. The reporter prints the usual console table and, at the
// end, one line per pair: kerf's median, the floor's median and their ratio,
// and where the kerf run counts the bytes it reads a step, those bytes over
// the machine's measured triad bandwidth.
#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <vector>

namespace kerf::bench {

/// `path` and `floor` are benchmark names with their arguments
/// ("BM_NodalExplicitStep/1/0"); registered before the benchmarks run.
void pair_with_floor(const std::string& path, const std::string& floor, const std::string& what);

/// A triad benchmark whose bandwidth turns a path's "bytes_per_step" counter
/// into a time (one column per triad, `label` its heading).
void use_bandwidth_of(const std::string& triad, const std::string& label);

class FloorReporter : public benchmark::ConsoleReporter {
 public:
  explicit FloorReporter(OutputOptions options) : ConsoleReporter(options) {}
  void ReportRuns(const std::vector<Run>& runs) override;
  void Finalize() override;

 private:
  struct Figures {
    std::vector<double> seconds;                    // per repetition, real time per iteration
    std::map<std::string, std::vector<double>> counters;
    double median_seconds = -1.0;                   // the "median" aggregate when reported
    std::map<std::string, double> median_counters;
  };
  /// Median seconds per iteration of a benchmark, negative when it did not run.
  double median_seconds(const std::string& name) const;
  double median_counter(const std::string& name, const std::string& counter) const;
  std::map<std::string, Figures> figures_;
};

}  // namespace kerf::bench
