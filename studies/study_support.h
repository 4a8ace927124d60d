#pragma once
// What the studies share: running a scene given as text (the scene is kept
// next to the results, so any point of a study can be run again by hand),
// progress lines, CSV tables, plots by Debian's python3, and claims.
#include <nlohmann/json.hpp>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "studies/study.h"

namespace kerf {

using Json = nlohmann::ordered_json;

class StudyRunner {
 public:
  StudyRunner(std::string study, const StudyOptions& options, int planned_runs);

  /// Writes `yaml` to <out>/scenes/<label>.yaml, runs it into <out>/runs/<label>
  /// and returns its summary.json (status "error" and the message when it failed:
  /// a study records a failed point and goes on).
  Json run(const std::string& label, const std::string& yaml, const std::vector<std::string>& overrides = {});
  /// The same as a separate `kerf run` on `ranks` MPI ranks (mpirun; 1: no
  /// mpirun) of `threads` OpenMP threads each; the summary gains `wall_s`,
  /// the launch's wall time.
  Json run_on_ranks(const std::string& label, const std::string& yaml, int ranks, int threads);
  /// A progress line (unless quiet).
  void say(const std::string& text) const;
  /// The progress line of a finished point.
  void report_point(const std::string& label, const Json& summary, double start);
  const std::string& out_dir() const { return out_; }

 private:
  std::string study_;
  std::string out_;
  bool quiet_;
  int planned_, done_ = 0;
  double start_;
};

/// A CSV file written row by row (numbers in full precision).
class CsvTable {
 public:
  CsvTable(const std::string& path, const std::vector<std::string>& columns);
  void row(const std::vector<Json>& values);

 private:
  std::string path_;
  std::size_t columns_;
};

/// A run's probes.csv as columns by name (time first), for studies that
/// look at a whole history rather than the final values.
using ProbeHistory = std::map<std::string, std::vector<double>>;
ProbeHistory read_probe_history(const std::string& run_dir);

/// The solvers and scaling studies' cube: 10 cm of corotational soft tissue
/// (E = 3 kPa, nu = 0.3) clamped at the bottom, sagging under gravity,
/// implicit Euler at 10 ms with one linearised solve a step (as SOFA does),
/// tet4 of `size` (m), `steps` steps, solved by `linear_solver` (with PETSc
/// options `petsc` when not empty) to 1e-8; a displacement probe named
/// `probe` at the top's centre.
std::string implicit_cube_scene(const std::string& name, double size, int steps, const std::string& linear_solver,
                                const std::string& petsc, const std::string& probe);

/// A phase's mean milliseconds a step, from a run's summary (0 when absent).
double phase_ms_per_step(const Json& summary, const std::string& phase, int steps);

/// Runs studies/plots/<script>.py on the study's folder with /usr/bin/python3.
void plot(const std::string& script, const std::string& out_dir);

/// A file the studies ship (scenes/..., studies/plots/...): from the source
/// tree kerf was built in while it exists, else from the installed data
/// (share/kerf beside the program's bin/, or under the configured prefix).
std::string study_data_path(const std::string& relative);

/// Writes <out>/<study>.json atomically.
void write_json(const std::string& path, const Json& value);

/// 100 (value - reference) / reference.
double percent_off(double value, double reference);

/// Least-squares slope of log |error| against log h: the observed order of convergence.
double observed_order(const std::vector<double>& h, const std::vector<double>& error);
/// A method's observed orders over its points (each with "spacing_m"): for
/// each {name, error key}, the order of that error; and "levels".
Json observed_orders(const std::vector<Json>& points, const std::vector<std::pair<std::string, std::string>>& errors);

/// A run's cost: the sum of its summary's phases (setup_s and solve_s leave out
/// the assembly the stepper's start does).
double whole_run_seconds(const Json& summary);

/// Throws "claim failed: ..." when `holds` is false.
void check_claim(bool holds, const std::string& claim);

}  // namespace kerf
