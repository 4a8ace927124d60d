#pragma once
// The run report as summary.json writes it: "counts", "timing" (setup_s,
// solve_s, phases, step_ms, cut_update_ms, cut_refresh_ms), "stages" and
// "solver" (the counters, the cut counters as cut_*, and the method's extras).
#include <nlohmann/json.hpp>

#include "core/run_report.h"

namespace kerf {

/// Writes (or overwrites) those keys of `summary` from `report`.
void write_report(const RunReport& report, nlohmann::ordered_json& summary);

/// What a run that threw `failure` says in summary.json: "status"
/// (`interrupted` or `error`), "error" (the message) and, for a solution
/// that diverged, "diverged": true. The one place those keys are decided.
void write_failure(const std::exception& failure, nlohmann::ordered_json& summary);

}  // namespace kerf
