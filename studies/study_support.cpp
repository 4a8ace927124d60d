#include "studies/study_support.h"

#include <malloc.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <thread>

#include "app/run_scene.h"
#include "app/summary_json.h"
#include "core/check.h"
#include "core/interrupt.h"
#include "core/timer.h"
#include "output/atomic_file.h"
#include "problem/scene_json.h"
#include "problem/scene_reader.h"

namespace kerf {

StudyRunner::StudyRunner(std::string study, const StudyOptions& options, int planned_runs)
    : study_(std::move(study)), out_(options.out_dir), quiet_(options.quiet), planned_(planned_runs),
      start_(now_seconds()) {
  std::filesystem::create_directories(out_ + "/scenes");
  std::filesystem::create_directories(out_ + "/runs");
}

Scene StudyRunner::write_scene(const std::string& label, const Scene& scene) const {
  const std::string file = out_ + "/scenes/" + label + ".yaml";
  Scene resolved = scene;
  resolved.output.dir = out_ + "/runs/" + label;
  const Json written = scene_to_json(resolved);
  write_file_atomically(file, "# kerf study " + study_ + ", point " + label +
                                  ": the resolved scene (every key) it ran; run again with: kerf run " + file + "\n" +
                                  written.dump(2) + "\n");
  Scene read = read_scene(file);
  KERF_CHECK(scene_to_json(read) == written, "internal: the study's scene ", file,
             " does not read back as the scene the study built");
  return read;
}

RunRecord StudyRunner::run(const std::string& label, const Scene& scene) {
  stop_if_interrupted("before the study's point ", label);
  ++done_;
  const double start = now_seconds();
  const std::string run_dir = out_ + "/runs/" + label;
  Json summary;
  try {
    RunOptions options;
    options.out_dir = run_dir;
    options.quiet = true;
    summary = run_scene(write_scene(label, scene), options).summary;
  } catch (const Interrupted&) {
    throw;  // a signal stops the study, not only its point
  } catch (const std::exception& e) {
    summary = Json::object();
    write_failure(e, summary);  // the keys run_scene wrote in the run's folder
  }
  // The point's memory back to the system: glibc keeps freed heap pages, and
  // the next point's estimate is held to the memory available (crack3d's
  // nodal 0.6 mm points were refused after EFG's, 14 of 24 GB available).
  malloc_trim(0);
  RunRecord record = record_of_summary(summary, run_dir);
  report_point(label, record, start);
  return record;
}

LaunchedRun StudyRunner::run_on_ranks(const std::string& label, const Scene& scene, int ranks, int threads) {
  const std::string scene_file = out_ + "/scenes/" + label + ".yaml";
  const std::string run_dir = out_ + "/runs/" + label;
  stop_if_interrupted("before the study's point ", label);
  write_scene(label, scene);
  std::filesystem::remove_all(run_dir);
  ++done_;
  // mpirun refuses root without --allow-run-as-root, and more ranks than cores without --oversubscribe.
  std::string command = "OMP_NUM_THREADS=" + std::to_string(threads) + " ";
  if (ranks > 1) {
    command += "mpirun -np " + std::to_string(ranks) + (geteuid() == 0 ? " --allow-run-as-root" : "");
    if (ranks > static_cast<int>(std::thread::hardware_concurrency())) command += " --oversubscribe";
    command += " ";
  }
  const std::string kerf = std::filesystem::read_symlink("/proc/self/exe").string();  // this very binary
  command += "'" + kerf + "' run '" + scene_file + "' --out '" + run_dir + "' --quiet 2>'" + run_dir + ".log'";
  const double start = now_seconds();
  const int status = std::system(command.c_str());
  LaunchedRun launched{{}, now_seconds() - start};
  // Ctrl-C reaches mpirun and its ranks (one process group); a SIGTERM sent
  // to the study alone is seen when the point ends.
  stop_if_interrupted("in the study's point ", label, " (run on ", ranks, " ranks)");
  const std::string where = "in the study's point " + label + " (run on " + std::to_string(ranks) + " ranks)";
  try {
    launched.run = read_outcome(run_dir);
  } catch (const Error& e) {
    launched.run.directory = run_dir;
    launched.run.status = RunStatus::error;
    launched.run.error = e.what();
  }
  if (launched.run.status == RunStatus::interrupted) throw Interrupted(SIGINT, where);
  if (status != 0) {
    launched.run.status = RunStatus::error;
    launched.run.error = command + " exited with " + std::to_string(status) + "; see " + run_dir + ".log";
  }
  report_point(label, launched.run, start);
  return launched;
}

void StudyRunner::report_point(const std::string& label, const RunRecord& run, double start) {
  const char* status[] = {"running", "ok", "error", "interrupted"};
  std::ostringstream line;
  line << "[" << done_ << "/" << planned_ << "] " << label << ": " << status[static_cast<int>(run.status)] << " in "
       << std::fixed << std::setprecision(1) << now_seconds() - start << " s (study " << now_seconds() - start_
       << " s)";
  if (run.status == RunStatus::error) line << "\n    " << run.error;
  say(line.str());
}

double phase_ms_per_step(const RunRecord& run, Phase phase, int steps) {
  return 1e3 * run.report.phases.seconds(phase) / steps;
}

void StudyRunner::say(const std::string& text) const {
  if (!quiet_) std::fprintf(stderr, "%s: %s\n", study_.c_str(), text.c_str());
}

CsvTable::CsvTable(const std::string& path, const std::vector<std::string>& columns)
    : path_(path), columns_(columns.size()) {
  std::ofstream out(path_);
  KERF_CHECK(out, "cannot write ", path_);
  for (std::size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
  out << "\n";
}

void CsvTable::row(const std::vector<Json>& values) {
  KERF_CHECK(values.size() == columns_, "internal: a row of ", values.size(), " values for ", columns_, " columns");
  std::ofstream out(path_, std::ios::app);
  KERF_CHECK(out, "cannot write ", path_);
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) out << ",";
    if (values[i].is_string())
      out << values[i].get<std::string>();
    else if (values[i].is_null())
      out << "";
    else
      out << values[i].dump();
  }
  out << "\n";
}

ProbeHistory read_probe_history(const std::string& run_dir) {
  const std::string path = run_dir + "/probes.csv";
  std::ifstream in(path);
  KERF_CHECK(in, "cannot read ", path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  ProbeHistory history;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    for (const std::string& name : names) {
      KERF_CHECK(std::getline(row, cell, ','), path, ": a row shorter than the header: ", line);
      history[name].push_back(std::stod(cell));
    }
  }
  return history;
}

std::string study_data_path(const std::string& relative) {
  std::error_code ignored;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", ignored);
  // The source tree; beside the program (an install moved with --prefix); the configured prefix.
  const std::string candidates[] = {std::string(KERF_SOURCE_DIR) + "/" + relative,
                                    (program.parent_path() / "../share/kerf" / relative).string(),
                                    std::string(KERF_INSTALLED_DATA_DIR) + "/" + relative};
  for (const std::string& path : candidates)
    if (std::filesystem::exists(path)) return path;
  return candidates[0];
}

void plot(const std::string& script, const std::string& out_dir) {
  const std::string path = study_data_path("studies/plots/" + script + ".py");
  const std::string command = "/usr/bin/python3 '" + path + "' '" + out_dir + "'";
  const int status = std::system(command.c_str());
  KERF_CHECK(status == 0, "the plot script ", path, " failed (exit ", status,
             "); the CSV and JSON results are written; expected Debian's python3 with python3-matplotlib and "
             "python3-numpy (make deps)");
}

StudyResult::StudyResult(std::string study, bool quick, std::vector<std::string> plots)
    : study_(std::move(study)), quick_(quick), plots_(std::move(plots)) {}

void StudyResult::headline(const std::string& what, const Json& value, const std::string& unit) {
  headline_.push_back({{"what", what}, {"value", value}, {"unit", unit}});
}

void StudyResult::set_headline(Json figures) { headline_ = std::move(figures); }

Json StudyResult::json() const {
  Json out = {{"study", study_}, {"quick", quick_}, {"headline", headline_}, {"plots", plots_}};
  for (const auto& [key, value] : sections_.items()) out[key] = value;
  return out;
}

void StudyResult::write(const std::string& out_dir) const {
  write_file_atomically(out_dir + "/" + study_ + ".json", json().dump(2) + "\n");
}

void check_claim(bool holds, const std::string& claim) {
  KERF_CHECK(holds, "claim failed: ", claim);
}

double percent_off(double value, double reference) { return 100.0 * (value - reference) / reference; }

double observed_order(const std::vector<double>& h, const std::vector<double>& error) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double x = std::log(h[i]), y = std::log(std::abs(error[i]));
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

Json observed_orders(const std::vector<Json>& points, const std::vector<std::pair<std::string, std::string>>& errors) {
  std::vector<double> h;
  for (const Json& p : points) h.push_back(p["spacing_m"]);
  Json orders = Json::object();
  for (const auto& [name, key] : errors) {
    std::vector<double> error;
    for (const Json& p : points) error.push_back(p[key]);
    orders[name] = observed_order(h, error);
  }
  orders["levels"] = points.size();
  return orders;
}

double whole_run_seconds(const RunRecord& run) {
  double seconds = 0.0;
  for (std::size_t p = 0; p < phase_names.size(); ++p) seconds += run.report.phases.seconds(static_cast<Phase>(p));
  return seconds;
}

}  // namespace kerf
