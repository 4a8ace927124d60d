#pragma once
// The run report as summary.json writes it: "counts", "timing" (setup_s,
// solve_s, phases, step_ms, cut_update_ms, cut_refresh_ms), "stages" and
// "solver" (the counters, the cut counters as cut_*, and the method's extras);
// and the same file read back, typed (read_outcome).
#include <nlohmann/json.hpp>

#include "app/run_record.h"
#include "core/run_report.h"

namespace kerf {

/// Writes (or overwrites) those keys of `summary` from `report`.
void write_report(const RunReport& report, nlohmann::ordered_json& summary);

/// What a run that threw `failure` says in summary.json: "status"
/// (`interrupted` or `error`), "error" (the message) and, for a solution
/// that diverged, "diverged": true. The one place those keys are decided.
void write_failure(const std::exception& failure, nlohmann::ordered_json& summary);

/// The typed record of a summary as run_scene writes it (`directory`: the
/// run's folder). The reader of the keys the two functions above write.
RunRecord record_of_summary(const nlohmann::ordered_json& summary, const std::string& directory);

/// Reads <directory>/summary.json into a record; throws kerf::Error naming
/// the file when it is missing or is not a run's summary.
RunRecord read_outcome(const std::string& directory);

}  // namespace kerf
