#include "floor_report.h"

#include <algorithm>
#include <cstdio>

namespace kerf::bench {
namespace {

struct Pair {
  std::string path, floor, what;
};

std::vector<Pair>& pairs() {
  static std::vector<Pair> registered;
  return registered;
}

struct Triad {
  std::string name, label;
};

std::vector<Triad>& triads() {
  static std::vector<Triad> registered;
  return registered;
}

double median(std::vector<double> values) {
  if (values.empty()) return -1.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// "BM_X/1/0" for every run of it, whatever iterations or repetitions were asked.
std::string key_of(const benchmark::BenchmarkReporter::Run& run) {
  const auto& name = run.run_name;
  return name.args.empty() ? name.function_name : name.function_name + "/" + name.args;
}

}  // namespace

void pair_with_floor(const std::string& path, const std::string& floor, const std::string& what) {
  pairs().push_back({path, floor, what});
}

void use_bandwidth_of(const std::string& triad, const std::string& label) { triads().push_back({triad, label}); }

void FloorReporter::ReportRuns(const std::vector<Run>& runs) {
  ConsoleReporter::ReportRuns(runs);
  for (const Run& run : runs) {
    if (run.error_occurred) continue;
    Figures& f = figures_[key_of(run)];
    const double seconds = run.GetAdjustedRealTime() / benchmark::GetTimeUnitMultiplier(run.time_unit);
    if (run.run_type == Run::RT_Iteration) {
      f.seconds.push_back(seconds);
      for (const auto& [counter, value] : run.counters) f.counters[counter].push_back(value.value);
    } else if (run.aggregate_name == "median") {
      f.median_seconds = seconds;
      for (const auto& [counter, value] : run.counters) f.median_counters[counter] = value.value;
    }
  }
}

double FloorReporter::median_seconds(const std::string& name) const {
  auto it = figures_.find(name);
  if (it == figures_.end()) return -1.0;
  return it->second.median_seconds >= 0.0 ? it->second.median_seconds : median(it->second.seconds);
}

double FloorReporter::median_counter(const std::string& name, const std::string& counter) const {
  auto it = figures_.find(name);
  if (it == figures_.end()) return -1.0;
  if (auto m = it->second.median_counters.find(counter); m != it->second.median_counters.end()) return m->second;
  if (auto c = it->second.counters.find(counter); c != it->second.counters.end()) return median(c->second);
  return -1.0;
}

void FloorReporter::Finalize() {
  ConsoleReporter::Finalize();
  std::vector<double> bandwidth;
  std::FILE* out = stdout;
  std::fprintf(out, "\nEach hot path against its floor (medians of the repetitions, real time per iteration)\n");
  for (const Triad& t : triads()) {
    bandwidth.push_back(median_counter(t.name, "bytes_per_second"));
    if (bandwidth.back() > 0)
      std::fprintf(out, "triad bandwidth, %s (%s): %.1f GB/s\n", t.label.c_str(), t.name.c_str(), 1e-9 * bandwidth.back());
  }
  std::fprintf(out, "%-48s %10s %10s %6s", "path", "kerf (ms)", "floor (ms)", "ratio");
  for (const Triad& t : triads()) std::fprintf(out, " %14s", ("bytes/" + t.label).c_str());
  std::fprintf(out, "\n");
  for (const Pair& p : pairs()) {
    const double kerf = median_seconds(p.path), floor = median_seconds(p.floor);
    if (kerf < 0 || floor < 0) continue;  // filtered out of this run
    const double bytes = median_counter(p.path, "bytes_per_step");
    std::fprintf(out, "%-48s %10.4f %10.4f %6.2f", p.path.c_str(), 1e3 * kerf, 1e3 * floor, kerf / floor);
    for (double b : bandwidth) {
      if (bytes > 0 && b > 0) std::fprintf(out, " %11.4f ms", 1e3 * bytes / b);
      else std::fprintf(out, " %14s", "-");
    }
    std::fprintf(out, "\n    floor %s: %s\n", p.floor.c_str(), p.what.c_str());
  }
  std::fflush(out);
}

}  // namespace kerf::bench
