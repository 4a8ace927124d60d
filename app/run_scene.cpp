#include "app/run_scene.h"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/probe_set.h"
#include "core/check.h"
#include "core/run_report.h"
#include "discretization/body_factory.h"
#include "geometry/cut_surface.h"
#include "kerf/version.h"
#include "output/atomic_file.h"
#include "output/probe_table.h"
#include "output/vtk_series.h"
#include "problem/scene_json.h"
#include "solvers/stepper.h"

namespace kerf {
namespace {

using json = nlohmann::ordered_json;

std::atomic<bool> interrupted{false};

}  // namespace

void refuse_unrunnable(const Scene& scene) {
  KERF_CHECK(scene.contact.empty(), scene.contact.front().where.describe(),
             ": contact is not implemented yet (it arrives with the studies, issue 5)");
  for (const Cut& cut : scene.cuts) {
    const bool fem = scene.discretization.method == Method::fem;
    KERF_CHECK(!fem || cut.fem != FemCut::remesh || scene.box, cut.where.describe(),
               ": key 'fem': value remesh: FEM remeshes around a cut only in a box domain (domain.mesh is read "
               "as it is); expected fem: remove, or domain.box");
    cut_surface(scene.dimension, cut.vertices, cut.times, cut.where.describe());
    for (std::size_t i = 0; i < cut.times.size(); ++i)
      KERF_CHECK(cut.times[i] <= 0.0 || scene.discretization.method == Method::nodal, cut.where.describe(),
                 ": key 'times': value ", cut.times[i], " at vertex ", i, ": a growing cut in ",
                 fem ? "FEM (remeshing or removing cells during the run, the state mapped over)"
                     : "efg (the Gauss points, loads and weak constraints updated)",
                 " is not built yet; expected discretization.method nodal, or every vertex present at t = 0");
  }
}

namespace {

json milliseconds_summary(std::vector<double> seconds) {
  if (seconds.empty()) return {{"median", 0.0}, {"mean", 0.0}, {"max", 0.0}};
  std::sort(seconds.begin(), seconds.end());
  double sum = 0.0;
  for (double s : seconds) sum += s;
  std::size_t n = seconds.size();
  double median = n % 2 ? seconds[n / 2] : 0.5 * (seconds[n / 2 - 1] + seconds[n / 2]);
  return {{"median", 1e3 * median}, {"mean", 1e3 * sum / n}, {"max", 1e3 * seconds.back()}};
}

void fill_report(json& summary, const RunReport& report) {
  json phases = json::object();
  for (const auto& [name, seconds] : report.phases.all()) phases[name + "_s"] = seconds;
  summary["timing"]["phases"] = phases;
  summary["timing"]["step_ms"] = milliseconds_summary(report.step_seconds);
  json cut_update = milliseconds_summary(report.cut_update_seconds);
  cut_update["count"] = report.cut_update_seconds.size();
  summary["timing"]["cut_update_ms"] = cut_update;
  json cut_refresh = milliseconds_summary(report.cut_refresh_seconds);
  cut_refresh["count"] = report.cut_refresh_seconds.size();
  summary["timing"]["cut_refresh_ms"] = cut_refresh;
  summary["stages"] = report.stages;
  if (!report.counters.empty()) summary["solver"] = report.counters;
}

/// A cut that grew by this state's time changes the body's shape functions
/// under the state; the stepper then re-reads what it keeps of them.
void advance_cuts(DiscreteBody& body, Stepper& stepper, SolverState& state, RunReport& report) {
  const double start = now_seconds();
  const std::optional<CutUpdate> update = body.advance_cuts(state.t);
  if (!update) return;
  const double updated = now_seconds();
  stepper.discretization_changed(state);
  const double refreshed = now_seconds();
  report.cut_update_seconds.push_back(updated - start);
  report.cut_refresh_seconds.push_back(refreshed - updated);
  report.phases.add("cut_update", refreshed - start);
  report.counters["cut_updated_nodes"] += update->nodes;
  report.counters["cut_updated_points"] += update->points;
}

}  // namespace

RunOutcome run_scene(const Scene& scene, const RunOptions& options) {
  refuse_unrunnable(scene);
  RunOutcome outcome;
  outcome.directory = options.out_dir.empty() ? scene.output.dir : options.out_dir;
  std::filesystem::create_directories(outcome.directory);
  const std::string summary_path = outcome.directory + "/summary.json";
  Scene resolved = scene;
  resolved.output.dir = outcome.directory;
  json& summary = outcome.summary;
  summary = {{"kerf_version", version}, {"scene", scene_to_json(resolved)}, {"status", "running"}};
  write_file_atomically(summary_path, summary.dump(2));

  RunReport report;
  const double start = now_seconds();
  auto previous_handler = std::signal(SIGINT, [](int) { interrupted = true; });
  interrupted = false;
  try {
    std::unique_ptr<DiscreteBody> body = make_body(scene, report);
    ProbeSet probes(scene, *body);
    std::unique_ptr<Stepper> stepper = make_stepper(*body, scene, report);
    SolverState state;
    stepper->initialize(state);  // timed inside as assembly and factorize
    summary["counts"] = {{"nodes", body->node_count()},
                         {"dofs", body->dof_count()},
                         {"elements", body->element_count()},
                         {"neighbors_mean", body->mean_neighbors()}};
    summary["timing"]["setup_s"] = now_seconds() - start;

    const int every = scene.output.vtk_every;
    std::unique_ptr<VtkSeries> vtk;
    if (every > 0) vtk = std::make_unique<VtkSeries>(outcome.directory, scene.name);
    std::vector<std::string> columns = probes.columns();
    columns.insert(columns.begin(), "time");
    ProbeTable table(outcome.directory + "/probes.csv", columns);
    EnergyState energy;
    std::size_t lattices_written_at = static_cast<std::size_t>(-1);  // cut growths when the grids were written
    Vector reaction, load_before, load_after, u_before;
    auto observe = [&](bool final_step) {
      ScopedTimer timer(report.phases, "output");
      if (probes.needs_reaction()) reaction = stepper->reaction(state);
      if (probes.needs_energy()) {
        energy.kinetic = stepper->kinetic_energy(state);
        energy.strain = body->strain_energy(state.u);
      }
      std::vector<double> row = probes.values(state, reaction, energy);
      row.insert(row.begin(), state.t);
      table.append(row);
      if (vtk) {
        BodySnapshot snapshot, cut;
        body->snapshot(state.u, snapshot);
        body->cut_snapshot(state.u, cut);
        // The grids' phi only when a cut grew since the last write (or at the first).
        const std::size_t growths = report.cut_update_seconds.size();
        std::vector<LatticeSnapshot> lattices;
        if (growths != lattices_written_at) lattices = body->enrichment_lattices();
        vtk->write(snapshot, state.t, &cut, growths != lattices_written_at ? &lattices : nullptr);
        lattices_written_at = growths;
        report.add_stage("vtk");
      }
      if (final_step) summary["probes"] = probes.final_values(state, reaction, energy);
    };
    observe(false);
    const int steps = stepper->step_count();
    const double dt = stepper->time_step();
    const bool static_run = scene.solve.analysis == Analysis::static_analysis;
    const int output_every = every > 0 ? every : 1;
    if (probes.needs_energy()) stepper->applied_load(state, load_before);
    const double loop_start = now_seconds();
    for (int i = 1; i <= steps; ++i) {
      KERF_CHECK(!interrupted, "interrupted (Ctrl-C) at step ", i, " of ", steps,
                 "; the results written so far are complete and readable");
      if (probes.needs_energy()) u_before = state.u;
      double step_start = now_seconds();
      stepper->advance(state, dt);
      report.step_seconds.push_back(now_seconds() - step_start);
      report.counters["newton_iterations"] += stepper->last_iterations();
      advance_cuts(*body, *stepper, state, report);
      if (probes.needs_energy()) {  // trapezoidal work of the applied loads
        stepper->applied_load(state, load_after);
        energy.external_work += 0.5 * (load_before + load_after).dot(state.u - u_before);
        load_before.swap(load_after);
      }
      bool last = i == steps;
      bool output_step = last || static_run || i % output_every == 0;
      if (output_step) observe(last);
      if (!options.quiet && (last || i % std::max(1, steps / 10) == 0))
        std::fprintf(stderr, "kerf: %s step %d/%d  t = %.6g  (%.3g s)\n", scene.name.c_str(), i, steps, state.t,
                     now_seconds() - start);
    }
    summary["timing"]["solve_s"] = now_seconds() - loop_start;
    fill_report(summary, report);
    summary["status"] = "ok";
    write_file_atomically(summary_path, summary.dump(2));
  } catch (const std::exception& e) {
    std::signal(SIGINT, previous_handler);
    fill_report(summary, report);
    summary["status"] = "error";
    summary["error"] = e.what();
    write_file_atomically(summary_path, summary.dump(2));
    throw;
  }
  std::signal(SIGINT, previous_handler);
  return outcome;
}

}  // namespace kerf
