#include "app/summary_json.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <omp.h>

#include "core/check.h"
#include "core/interrupt.h"
#include "core/module_loader.h"
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

/// The modules (core/module_loader.h) this process loaded by now, and what
/// each cost: what a run did not need is not there.
json modules_json() {
  json out = json::object();
  for (const LoadedModule& m : loaded_modules()) out[m.name] = {{"load_ms", m.load_ms}, {"libraries", m.libraries}};
  return out;
}

/// Every counter of the "solver" section by its key, in the file's order: the
/// one list the writer and the reader share (`Report` const or not).
template <class Report, class Visit>
void visit_counters(Report& report, Visit&& visit) {
  auto& s = report.solver;
  auto& c = report.cuts;
  visit("factorizations", s.factorizations);
  visit("linear_iterations", s.linear_iterations);
  visit("pcg_iterations", s.pcg_iterations);
  visit("newton_iterations", s.newton_iterations);
  visit("contact_augmentations", s.contact_augmentations);
  visit("definite_tangent_fallbacks", s.definite_tangent_fallbacks);
  visit("increments_taken", s.increments_taken);
  visit("cutbacks", s.cutbacks);
  visit("cut_remeshes", c.remeshes);
  visit("cut_removed_cells", c.removed_cells);
  visit("cut_updated_nodes", c.updated_nodes);
  visit("cut_updated_points", c.updated_points);
  visit("cut_split_cells", c.split_cells);
  visit("cut_duplicated_nodes", c.duplicated_nodes);
  visit("cut_dropped_volume", c.dropped_volume);
  visit("cut_front_points", c.front_points);
  visit("cut_front_unresolved", c.front_unresolved);
}

/// The optional figures of the "solver" section, likewise.
template <class Report, class Visit>
void visit_optional_figures(Report& report, Visit&& visit) {
  auto& s = report.solver;
  visit("smallest_increment", s.smallest_increment);
  visit("critical_dt_s", s.critical_dt_s);
  visit("critical_dt_element_bound_s", s.critical_dt_element_bound_s);
  visit("critical_dt_min_s", s.critical_dt_min_s);
}

template <class Report, class Visit>
void visit_newton_endings(Report& report, Visit&& visit) {
  auto& by = report.solver.newton_converged_by;
  visit("relative", by.relative);
  visit("absolute", by.absolute);
  visit("step", by.step);
}

json solver_counters(const RunReport& report) {
  json out = json::object();
  json endings = json::object();
  visit_newton_endings(report, [&](const char* name, long value) { endings[name] = value; });
  visit_counters(report, [&](const char* name, const auto& value) {
    out[name] = value;
    if (std::string(name) == "cutbacks") out["newton_converged_by"] = endings;  // the file's order
  });
  visit_optional_figures(report, [&](const char* name, const std::optional<double>& value) {
    if (value) out[name] = *value;
  });
  if (report.solver.critical_dt_min_s) out["substeps_max"] = report.solver.substeps_max;
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
                         {"mesh_divided", r.mesh_divided},
                         {"state_in_pieces", r.state_in_pieces},
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
                       {"cut_refresh_ms", counted_milliseconds(report.cut_refresh_seconds)},
                       {"modules", modules_json()}};
  summary["stages"] = report.stages;
  summary["notes"] = report.notes;
  summary["solver"] = solver_counters(report);
}

void write_failure(const std::exception& failure, json& summary) {
  summary["status"] = dynamic_cast<const Interrupted*>(&failure) ? "interrupted" : "error";
  summary["error"] = failure.what();
  if (dynamic_cast<const Diverged*>(&failure)) summary["diverged"] = true;
}

namespace {

RunStatus status_of(const std::string& word, const std::string& file) {
  const std::pair<const char*, RunStatus> words[] = {{"running", RunStatus::running},
                                                     {"ok", RunStatus::ok},
                                                     {"error", RunStatus::error},
                                                     {"interrupted", RunStatus::interrupted}};
  for (const auto& [spelling, status] : words)
    if (word == spelling) return status;
  throw Error(file + ": key 'status': value '" + word + "' is not a run's status; expected running, ok, error or interrupted");
}

DurationStats duration_stats(const json& section) {
  return {section.value("median", 0.0), section.value("mean", 0.0), section.value("max", 0.0),
          section.value("count", 0L)};
}

/// A probe's final values by the keys ProbeSet::final_values writes.
ProbeReading probe_reading(const json& value) {
  if (value.contains("kinetic"))
    return {ProbeField::energy, {value["kinetic"].get<double>(), value["strain"].get<double>(),
                                 value["external_work"].get<double>(), value["total"].get<double>()}};
  for (const ProbeField field : {ProbeField::displacement, ProbeField::reaction, ProbeField::contact_force,
                                 ProbeField::indentation})
    if (value.contains(to_string(field))) {
      const json& v = value[to_string(field)];
      return {field, v.is_array() ? v.get<std::vector<double>>() : std::vector<double>{v.get<double>()}};
    }
  throw Error("a probe's value " + value.dump() + " names no probe field");
}

void read_counts_and_ranks(const json& summary, RunReport& report) {
  const json& counts = summary.at("counts");
  report.counts = {counts.at("nodes").get<Index>(), counts.at("dofs").get<Index>(),
                   counts.at("elements").get<Index>(), counts.at("neighbors_mean").get<double>()};
  const json& ranks = summary.at("parallel");
  RankCounts& r = report.parallel;
  r.ranks = ranks.at("ranks").get<int>();
  r.partitioned = ranks.at("partitioned").get<bool>();
  r.mesh_divided = ranks.value("mesh_divided", false);  // summaries before issue 38 lack it
  r.state_in_pieces = ranks.value("state_in_pieces", false);  // and before its ghosted explicit state
  r.owned_rows = ranks.at("rank0_owned_rows").get<Index>();
  r.touched_rows = ranks.at("rank0_touched_rows").get<Index>();
  if (ranks.contains("peak_memory_mb_by_rank")) {
    const json& marks = ranks["peak_memory_mb_by_rank"];
    for (std::size_t k = 0; k < marks.at("at_end").size(); ++k)
      r.memory_by_rank.push_back({marks["after_body"][k].get<double>(), marks["after_initialization"][k].get<double>(),
                                  marks["at_end"][k].get<double>()});
  }
}

void read_timing(const json& timing, RunRecord& record) {
  RunReport& report = record.report;
  report.setup_seconds = timing.at("setup_s").get<double>();
  report.solve_seconds = timing.at("solve_s").get<double>();
  for (std::size_t p = 0; p < phase_names.size(); ++p)
    report.phases.add(static_cast<Phase>(p), timing.at("phases").at(std::string(phase_names[p]) + "_s").get<double>());
  record.step_ms = duration_stats(timing.at("step_ms"));
  record.cut_update_ms = duration_stats(timing.at("cut_update_ms"));
  record.cut_refresh_ms = duration_stats(timing.at("cut_refresh_ms"));
}

void read_solver(const json& solver, RunReport& report) {
  json rest = solver;  // what no typed field takes: the method's extras
  visit_counters(report, [&](const char* name, auto& value) {
    value = solver.at(name).get<std::remove_reference_t<decltype(value)>>();
    rest.erase(name);
  });
  visit_newton_endings(report, [&](const char* name, long& value) { value = solver.at("newton_converged_by").at(name); });
  rest.erase("newton_converged_by");
  visit_optional_figures(report, [&](const char* name, std::optional<double>& value) {
    if (solver.contains(name)) value = solver[name].get<double>();
    rest.erase(name);
  });
  if (solver.contains("substeps_max")) report.solver.substeps_max = solver["substeps_max"].get<int>();
  rest.erase("substeps_max");
  for (const auto& [name, value] : rest.items()) report.extras[name] = value.get<double>();
}

}  // namespace

RunRecord record_of_summary(const json& summary, const std::string& directory) {
  const std::string file = directory + "/summary.json";
  RunRecord record;
  record.directory = directory;
  try {
    record.status = status_of(summary.at("status").get<std::string>(), file);
    record.error = summary.value("error", "");
    record.diverged = summary.value("diverged", false);
    if (!summary.contains("counts")) return record;  // refused before any report (a failed read, a launch that died)
    read_counts_and_ranks(summary, record.report);
    record.peak_memory_mb = summary["parallel"].value("rank0_peak_memory_mb", 0.0);
    read_timing(summary.at("timing"), record);
    record.report.stages = summary.at("stages").get<std::vector<std::string>>();
    record.report.notes = summary.at("notes").get<std::vector<std::string>>();
    read_solver(summary.at("solver"), record.report);
    if (summary.contains("probes"))
      for (const auto& [name, value] : summary["probes"].items()) record.probes[name] = probe_reading(value);
  } catch (const json::exception& e) {
    throw Error(file + ": not a run's summary as kerf writes it (" + e.what() + ")");
  }
  return record;
}

RunRecord read_outcome(const std::string& directory) {
  const std::string file = directory + "/summary.json";
  std::ifstream in(file);
  if (!in) throw Error(file + ": cannot be read (no run wrote it)");
  const json summary = json::parse(in, nullptr, false);
  if (summary.is_discarded()) throw Error(file + ": is not JSON (a run stopped while writing it?)");
  return record_of_summary(summary, directory);
}

double RunRecord::probe(const std::string& name, int component) const {
  const auto found = probes.find(name);
  if (found == probes.end()) throw Error(directory + "/summary.json: the run has no probe named '" + name + "'");
  if (component < 0 || component >= static_cast<int>(found->second.values.size()))
    throw Error(directory + "/summary.json: probe '" + name + "' has no value " + std::to_string(component));
  return found->second.values[component];
}

double RunRecord::extra(const std::string& name) const {
  const auto found = report.extras.find(name);
  return found == report.extras.end() ? NAN : found->second;
}

}  // namespace kerf
