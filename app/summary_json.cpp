#include "app/summary_json.h"

#include <algorithm>

#include <omp.h>

#include "core/check.h"
#include "core/interrupt.h"
#include "core/peak_memory.h"
#include "core/thread_policy.h"

namespace kerf {
namespace {

using json = nlohmann::ordered_json;

json milliseconds_summary(std::vector<double> seconds) {
  if (seconds.empty()) return {{"median", 0.0}, {"mean", 0.0}, {"max", 0.0}};
  std::sort(seconds.begin(), seconds.end());
  double sum = 0.0;
  for (double s : seconds) sum += s;
  const std::size_t n = seconds.size();
  const double median = n % 2 ? seconds[n / 2] : 0.5 * (seconds[n / 2 - 1] + seconds[n / 2]);
  return {{"median", 1e3 * median}, {"mean", 1e3 * sum / n}, {"max", 1e3 * seconds.back()}};
}

json counted_milliseconds(const std::vector<double>& seconds) {
  json out = milliseconds_summary(seconds);
  out["count"] = seconds.size();
  return out;
}

json solver_counters(const RunReport& report) {
  const SolverCounters& s = report.solver;
  const CutCounters& c = report.cuts;
  json out = {{"factorizations", s.factorizations},
              {"linear_iterations", s.linear_iterations},
              {"pcg_iterations", s.pcg_iterations},
              {"newton_iterations", s.newton_iterations},
              {"contact_augmentations", s.contact_augmentations},
              {"definite_tangent_fallbacks", s.definite_tangent_fallbacks},
              {"increments_taken", s.increments_taken},
              {"cutbacks", s.cutbacks},
              {"newton_converged_by",
               {{"relative", s.newton_converged_by.relative},
                {"absolute", s.newton_converged_by.absolute},
                {"step", s.newton_converged_by.step}}},
              {"cut_remeshes", c.remeshes},
              {"cut_removed_cells", c.removed_cells},
              {"cut_updated_nodes", c.updated_nodes},
              {"cut_updated_points", c.updated_points},
              {"cut_split_cells", c.split_cells},
              {"cut_duplicated_nodes", c.duplicated_nodes},
              {"cut_dropped_volume", c.dropped_volume},
              {"cut_front_points", c.front_points},
              {"cut_front_unresolved", c.front_unresolved}};
  if (s.smallest_increment) out["smallest_increment"] = *s.smallest_increment;
  if (s.critical_dt_s) out["critical_dt_s"] = *s.critical_dt_s;
  if (s.critical_dt_element_bound_s) out["critical_dt_element_bound_s"] = *s.critical_dt_element_bound_s;
  if (s.critical_dt_min_s) {
    out["critical_dt_min_s"] = *s.critical_dt_min_s;
    out["substeps_max"] = s.substeps_max;
  }
  for (const auto& [name, value] : report.extras) out[name] = value;
  return out;
}

}  // namespace

void write_report(const RunReport& report, json& summary) {
  const RunCounts& n = report.counts;
  summary["counts"] = {
      {"nodes", n.nodes}, {"dofs", n.dofs}, {"elements", n.elements}, {"neighbors_mean", n.neighbors_mean}};
  const RankCounts& r = report.parallel;
  summary["parallel"] = {{"ranks", r.ranks},
                         {"partitioned", r.partitioned},
                         {"rank0_owned_rows", r.owned_rows},
                         {"rank0_touched_rows", r.touched_rows},
                         {"rank0_peak_memory_mb", peak_memory_mb()}};
  const std::string limited_by = thread_policy_field("limited_by");
  summary["parallel"]["threads"] = {{"count", omp_get_max_threads()},
                                    {"wait_policy", wait_policy_in_effect()},
                                    {"limited_by", limited_by.empty() ? "set outside kerf" : limited_by}};
  if (!r.memory_by_rank.empty()) {
    json& marks = summary["parallel"]["peak_memory_mb_by_rank"];
    marks = {{"after_body", json::array()}, {"after_initialization", json::array()}, {"at_end", json::array()}};
    for (const MemoryMarks& m : r.memory_by_rank) {
      marks["after_body"].push_back(m.after_body);
      marks["after_initialization"].push_back(m.after_initialization);
      marks["at_end"].push_back(m.at_end);
    }
  }
  json phases = json::object();
  for (std::size_t p = 0; p < phase_names.size(); ++p)
    phases[std::string(phase_names[p]) + "_s"] = report.phases.seconds(static_cast<Phase>(p));
  summary["timing"] = {{"setup_s", report.setup_seconds},
                       {"solve_s", report.solve_seconds},
                       {"phases", phases},
                       {"step_ms", counted_milliseconds(report.step_seconds)},
                       {"cut_update_ms", counted_milliseconds(report.cut_update_seconds)},
                       {"cut_refresh_ms", counted_milliseconds(report.cut_refresh_seconds)}};
  summary["stages"] = report.stages;
  summary["notes"] = report.notes;
  summary["solver"] = solver_counters(report);
}

void write_failure(const std::exception& failure, json& summary) {
  summary["status"] = dynamic_cast<const Interrupted*>(&failure) ? "interrupted" : "error";
  summary["error"] = failure.what();
  if (dynamic_cast<const Diverged*>(&failure)) summary["diverged"] = true;
}

}  // namespace kerf
