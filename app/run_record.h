#pragma once
// What a finished (or failed) run's summary.json says, typed: the answer a
// study, the MPI study runner or the Python module reads instead of keys.
// app/summary_json writes the file and reads it back (read_outcome).
#include <map>
#include <string>
#include <vector>

#include "core/run_report.h"
#include "problem/scene.h"

namespace kerf {

enum class RunStatus { running, ok, error, interrupted };

/// The statistics summary.json keeps of a list of durations (each step,
/// each growth of a cut): the list itself is not in the file.
struct DurationStats {
  double median_ms = 0.0, mean_ms = 0.0, max_ms = 0.0;
  long count = 0;
};

/// A probe's value at the end of the run.
struct ProbeReading {
  ProbeField field = ProbeField::displacement;
  /// displacement, reaction, contact_force: one per axis of the scene;
  /// indentation: one; energy: kinetic, strain, external_work, total (J).
  std::vector<double> values;
};

struct RunRecord {
  std::string directory;  // the run's folder
  RunStatus status = RunStatus::running;
  std::string error;       // error, interrupted: the message
  bool diverged = false;   // the solution blew up (central differences: NaN)
  /// The report as written; its per-step and per-growth time lists stay
  /// empty (the file keeps their statistics, below).
  RunReport report;
  DurationStats step_ms, cut_update_ms, cut_refresh_ms;
  double peak_memory_mb = 0.0;  // rank 0's when the summary was written
  std::map<std::string, ProbeReading> probes;

  bool ok() const { return status == RunStatus::ok; }
  /// The probe's `component`-th value; throws naming the probe when the run has none of that name.
  double probe(const std::string& name, int component = 0) const;
  /// A method's figure from the solver section (report.extras; NaN when the run has none).
  double extra(const std::string& name) const;
};

}  // namespace kerf
