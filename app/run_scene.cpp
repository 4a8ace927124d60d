#include "app/run_scene.h"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/probe_set.h"
#include "app/summary_json.h"
#include "core/check.h"
#include "core/run_report.h"
#include "discretization/body_factory.h"
#include "discretization/fem/state_transfer.h"
#include "kerf/version.h"
#include "output/atomic_file.h"
#include "output/probe_table.h"
#include "output/vtk_series.h"
#include "problem/scene_json.h"
#include "problem/scene_validation.h"
#include "solvers/stepper.h"

namespace kerf {
namespace {

using json = nlohmann::ordered_json;

std::atomic<bool> interrupted{false};

}  // namespace

SharedCuts refuse_unrunnable(const Scene& scene) {
  validate(scene);
  return std::make_shared<const CutTimeline>(scene);
}

namespace {

/// What a run holds on its body: body and stepper replaced when FEM meshes
/// again, probes resolved again after any cut growth.
struct RunParts {
  std::unique_ptr<DiscreteBody> body;
  std::unique_ptr<ProbeSet> probes;
  std::unique_ptr<Stepper> stepper;
};

/// FEM and a cut that grew by this state's time: the body is meshed again
/// with the pieces present (or more cells removed), the state carried onto the
/// new nodes, the stepper made again on the new body (the run loop resolves
/// the probes again after any growth). Timed like a
/// meshless update: cut_update_ms (mesh, body, state transfer) and
/// cut_refresh_ms (the new stepper reading mass and forces).
void remesh_for_cuts(const Scene& scene, const SharedCuts& cuts, RunParts& run, SolverState& state,
                     RunReport& report) {
  const double start = now_seconds();
  RunReport remesh_report;  // its setup phase is the cut update's, not the run's
  std::unique_ptr<DiscreteBody> body = make_body(scene, cuts, remesh_report, state.t);
  const StateTransfer transfer(dynamic_cast<const FemBody&>(*run.body), dynamic_cast<const FemBody&>(*body));
  state.u = transfer(state.u);
  state.v = transfer(state.v);
  state.a = transfer(state.a);
  const double updated = now_seconds();
  run.stepper = make_stepper(*body, scene, report);
  run.stepper->discretization_changed(state);
  run.body = std::move(body);
  const double refreshed = now_seconds();
  report.cut_update_seconds.push_back(updated - start);
  report.cut_refresh_seconds.push_back(refreshed - updated);
  report.phases.add(Phase::cut_update, refreshed - start);
  report.cuts.removed_cells += remesh_report.cuts.removed_cells;
  report.cuts.remeshes += 1;
  report.cuts.updated_nodes += run.body->node_count();
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
  report.phases.add(Phase::cut_update, refreshed - start);
  report.cuts.updated_nodes += update->nodes;
  report.cuts.updated_points += update->points;
}

}  // namespace

RunOutcome run_scene(const Scene& scene, const RunOptions& options) {
  const SharedCuts cuts = refuse_unrunnable(scene);
  RunOutcome outcome;
  outcome.directory = options.out_dir.empty() ? scene.output.dir : options.out_dir;
  std::filesystem::create_directories(outcome.directory);
  const std::string summary_path = outcome.directory + "/summary.json";
  Scene resolved = scene;
  resolved.output.dir = outcome.directory;
  json& summary = outcome.summary;
  summary = {{"kerf_version", version}, {"scene", scene_to_json(resolved)}, {"status", "running"}};
  write_file_atomically(summary_path, summary.dump(2));

  RunReport& report = outcome.report;
  const double start = now_seconds();
  auto previous_handler = std::signal(SIGINT, [](int) { interrupted = true; });
  interrupted = false;
  try {
    RunParts run;
    run.body = make_body(scene, cuts, report);
    run.probes = std::make_unique<ProbeSet>(scene, *run.body);
    run.stepper = make_stepper(*run.body, scene, report);
    SolverState state;
    run.stepper->initialize(state);  // timed inside as assembly and factorize
    report.counts = {run.body->node_count(), run.body->dof_count(), run.body->element_count(),
                     run.body->mean_neighbors()};
    // FEM follows a growing cut by meshing again when pieces appear.
    Index fem_pieces = scene.discretization.method == Method::fem ? cuts->pieces_at(0.0) : 0;
    report.setup_seconds = now_seconds() - start;

    const int every = scene.output.vtk_every;
    std::unique_ptr<VtkSeries> vtk;
    if (every > 0) vtk = std::make_unique<VtkSeries>(outcome.directory, scene.name);
    std::vector<std::string> columns = run.probes->columns();
    columns.insert(columns.begin(), "time");
    ProbeTable table(outcome.directory + "/probes.csv", columns);
    EnergyState energy;
    std::size_t lattices_written_at = static_cast<std::size_t>(-1);  // cut growths when the grids were written
    Vector reaction, load_before, load_after, u_before;
    auto observe = [&](bool final_step) {
      ScopedTimer timer(report.phases, Phase::output);
      if (run.probes->needs_reaction()) reaction = run.stepper->reaction(state);
      if (run.probes->needs_energy()) {
        energy.kinetic = run.stepper->kinetic_energy(state);
        energy.strain = run.body->strain_energy(state.u);
      }
      std::vector<double> row = run.probes->values(state, reaction, energy);
      row.insert(row.begin(), state.t);
      table.append(row);
      if (vtk) {
        BodySnapshot snapshot, cut;
        run.body->snapshot(state.u, snapshot);
        run.body->cut_snapshot(state.u, cut);
        // The grids' phi only when a cut grew since the last write (or at the first).
        const std::size_t growths = report.cut_update_seconds.size();
        std::vector<LatticeSnapshot> lattices;
        if (growths != lattices_written_at) lattices = run.body->enrichment_lattices();
        vtk->write(snapshot, state.t, &cut, growths != lattices_written_at ? &lattices : nullptr);
        lattices_written_at = growths;
        report.add_stage("vtk");
      }
      if (final_step) summary["probes"] = run.probes->final_values(state, reaction, energy);
    };
    observe(false);
    const int steps = run.stepper->step_count();
    const double dt = run.stepper->time_step();
    const bool static_run = scene.solve.analysis == Analysis::static_analysis;
    const int output_every = every > 0 ? every : 1;
    if (run.probes->needs_energy()) run.stepper->applied_load(state, load_before);
    const double loop_start = now_seconds();
    for (int i = 1; i <= steps; ++i) {
      KERF_CHECK(!interrupted, "interrupted (Ctrl-C) at step ", i, " of ", steps,
                 "; the results written so far are complete and readable");
      if (run.probes->needs_energy()) u_before = state.u;
      double step_start = now_seconds();
      run.stepper->advance(state, dt);
      report.step_seconds.push_back(now_seconds() - step_start);
      report.solver.newton_iterations += run.stepper->last_iterations();
      if (run.probes->needs_energy()) {  // trapezoidal work of the applied loads, before a cut changes the dofs
        run.stepper->applied_load(state, load_after);
        energy.external_work += 0.5 * (load_before + load_after).dot(state.u - u_before);
        load_before.swap(load_after);
      }
      const std::size_t growths = report.cut_update_seconds.size();
      if (const Index now = cuts->pieces_at(state.t); scene.discretization.method == Method::fem && now != fem_pieces) {
        remesh_for_cuts(scene, cuts, run, state, report);
        fem_pieces = now;
      } else {
        advance_cuts(*run.body, *run.stepper, state, report);
      }
      if (report.cut_update_seconds.size() != growths) {
        // Probes interpolate with the new shape functions or mesh (a probe on
        // a face now sees its own side only), and the loads as the new
        // discretization integrates them.
        run.probes = std::make_unique<ProbeSet>(scene, *run.body);
        if (run.probes->needs_energy()) run.stepper->applied_load(state, load_before);
      }
      bool last = i == steps;
      bool output_step = last || static_run || i % output_every == 0;
      if (output_step) observe(last);
      if (!options.quiet && (last || i % std::max(1, steps / 10) == 0))
        std::fprintf(stderr, "kerf: %s step %d/%d  t = %.6g  (%.3g s)\n", scene.name.c_str(), i, steps, state.t,
                     now_seconds() - start);
    }
    report.solve_seconds = now_seconds() - loop_start;
    run.body->add_diagnostics(report.extras);
    write_report(report, summary);
    summary["status"] = "ok";
    write_file_atomically(summary_path, summary.dump(2));
  } catch (const std::exception& e) {
    std::signal(SIGINT, previous_handler);
    write_report(report, summary);
    summary["status"] = "error";
    summary["error"] = e.what();
    write_file_atomically(summary_path, summary.dump(2));
    throw;
  }
  std::signal(SIGINT, previous_handler);
  return outcome;
}

}  // namespace kerf
