#pragma once
// What the studies share: running a Scene (its resolved file is kept next to
// the results, so any point of a study can be run again by hand) and reading
// its typed record, progress lines, CSV tables, plots by Debian's python3,
// and claims. The scenes' common parts are in studies/study_scenes.h.
#include <nlohmann/json.hpp>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "app/run_record.h"
#include "problem/scene.h"
#include "studies/study.h"

namespace kerf {

using Json = nlohmann::ordered_json;

/// A point run as its own `kerf run` (mpirun): its record and the launch's wall time.
struct LaunchedRun {
  RunRecord run;
  double wall_s = 0.0;
};

class StudyRunner {
 public:
  StudyRunner(std::string study, const StudyOptions& options, int planned_runs);

  /// Writes `scene` resolved (every key, as `kerf check` echoes it) to
  /// <out>/scenes/<label>.yaml, reads that file back and runs it into
  /// <out>/runs/<label>: the file is what ran, and `kerf run` runs it again.
  /// A failed point answers status error and the message (a study records
  /// it and goes on); a signal stops the study.
  RunRecord run(const std::string& label, const Scene& scene);
  /// The same as a separate `kerf run` on `ranks` MPI ranks (mpirun; 1: no
  /// mpirun) of `threads` OpenMP threads each, its record read back from its
  /// summary.json.
  LaunchedRun run_on_ranks(const std::string& label, const Scene& scene, int ranks, int threads);
  /// Writes <out>/scenes/<label>.yaml (output.dir: <out>/runs/<label>) and
  /// answers the scene read back from it; throws when the file would not run
  /// what `scene` says (an internal error of the study). For a study's work
  /// that is not a run (a spectrum), so that its scene is kept all the same.
  Scene write_scene(const std::string& label, const Scene& scene) const;
  /// A progress line (unless quiet).
  void say(const std::string& text) const;
  const std::string& out_dir() const { return out_; }

 private:
  void report_point(const std::string& label, const RunRecord& run, double start);

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

/// A phase's mean milliseconds a step over a run's `steps` steps.
double phase_ms_per_step(const RunRecord& run, Phase phase, int steps);

/// Runs studies/plots/<script>.py on the study's folder with /usr/bin/python3.
void plot(const std::string& script, const std::string& out_dir);

/// A file the studies ship (scenes/..., studies/plots/...): from the source
/// tree kerf was built in while it exists, else from the installed data
/// (share/kerf beside the program's bin/, or under the configured prefix).
std::string study_data_path(const std::string& relative);

/// <study>.json: the envelope every study writes first (study, quick,
/// headline: {what, value, unit} figures the main job's README lists, plots),
/// then the study's own sections in the order it sets them.
class StudyResult {
 public:
  StudyResult(std::string study, bool quick, std::vector<std::string> plots);
  void headline(const std::string& what, const Json& value, const std::string& unit);
  /// A study that composes its headline list itself (each item what, value, unit).
  void set_headline(Json figures);
  Json& operator[](const std::string& section) { return sections_[section]; }
  /// The file's content.
  Json json() const;
  /// Writes <out_dir>/<study>.json atomically.
  void write(const std::string& out_dir) const;

 private:
  std::string study_;
  bool quick_;
  Json headline_ = Json::array(), plots_, sections_ = Json::object();
};

/// 100 (value - reference) / reference.
double percent_off(double value, double reference);

/// Least-squares slope of log |error| against log h: the observed order of convergence.
double observed_order(const std::vector<double>& h, const std::vector<double>& error);
/// A method's observed orders over its points (each with "spacing_m"): for
/// each {name, error key}, the order of that error; and "levels".
Json observed_orders(const std::vector<Json>& points, const std::vector<std::pair<std::string, std::string>>& errors);

/// A run's cost: the sum of its phases (setup_s and solve_s leave out
/// the assembly the stepper's start does).
double whole_run_seconds(const RunRecord& run);

/// Throws "claim failed: ..." when `holds` is false.
void check_claim(bool holds, const std::string& claim);

}  // namespace kerf
