#include "app/run_scene.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "app/cut_follower.h"
#include "app/resource_estimate.h"
#include "app/run_observer.h"
#include "app/run_parts.h"
#include "app/summary_json.h"
#include "core/check.h"
#include "core/interrupt.h"
#include "core/peak_memory.h"
#include "core/progress_heartbeat.h"
#include "core/rank_share.h"
#include "discretization/body_capabilities.h"
#include "discretization/body_factory.h"
#include "kerf/version.h"
#include "output/atomic_file.h"
#include "problem/scene_json.h"
#include "problem/scene_validation.h"
#include "solvers/petsc_session.h"
#include "solvers/rank_sum.h"

namespace kerf {
namespace {

using json = nlohmann::ordered_json;

/// summary.json's text; bytes that are not UTF-8 (a path given on the command
/// line, an error quoting one) become U+FFFD rather than stop the writing.
std::string summary_text(const json& summary) { return summary.dump(2, ' ', false, json::error_handler_t::replace); }

/// Puts the resource estimate in the summary and refuses a run that cannot fit (unless forced).
ResourceEstimate estimate_and_guard(const Scene& scene, const RunOptions& options, const std::string& directory,
                                    json& summary) {
  const ResourceEstimate estimate = estimate_resources(scene, options.mpi.ranks.count);
  summary["estimate"] = estimate_to_json(estimate);
  if (!options.force) {
    refuse_what_cannot_fit(scene, estimate, memory_limit_mb(options.mpi.ranks));
    if (options.writes_files()) refuse_output_that_cannot_fit(scene, estimate, directory);
  }
  return estimate;
}

/// gmsh says nothing while it meshes: a set-up that meshes more than a million
/// cells says so first and then shows it is alive every 10 s.
std::optional<ProgressHeartbeat> announce_long_meshing(const Scene& scene, const RunOptions& options,
                                                       const ResourceEstimate& estimate) {
  if (options.quiet || estimate.mesh_cells <= 1e6) return std::nullopt;
  std::fprintf(stderr, "kerf: %s: meshing about %.3g cells (estimated; kerf check prints the estimate)\n",
               scene.name.c_str(), estimate.mesh_cells);
  char what[256];
  std::snprintf(what, sizeof what, "%s: still setting up (gmsh meshing about %.3g cells, then the system; "
                "Ctrl-C stops it)", scene.name.c_str(), estimate.mesh_cells);
  return std::optional<ProgressHeartbeat>(std::in_place, what, std::chrono::seconds(10));
}

/// The watchdog's last words when a signal cannot be honoured in time (in
/// gmsh, in a factorization): `summary` written to `path` ("" writes
/// nothing: another rank writes), saying the run was stopped at once.
std::function<void(int)> summary_saying_interrupted(const std::string& path, json summary) {
  return [path, summary](int signal) mutable {
    if (path.empty()) return;
    summary["status"] = "interrupted";
    summary["error"] = std::string("interrupted (") + (signal == SIGTERM ? "SIGTERM" : "SIGINT, Ctrl-C") +
                       ") in the set-up or a solve, which could not stop within " +
                       std::to_string(static_cast<int>(interrupt_grace_seconds)) + " s; stopped at once";
    try {
      write_file_atomically(path, summary_text(summary));
    } catch (...) {  // the process ends now whatever happens
    }
  };
}

/// The body at the end of the run, as ParaView gets it.
std::shared_ptr<const BodySnapshot> final_body(const RunParts& run, const SolverState& state) {
  auto body = std::make_shared<BodySnapshot>();
  Vector body_u;
  run.body->snapshot(run.mechanics->body_part(state.u, body_u), *body);
  return body;
}

/// The body, its mechanical system, stepper and probes, the initial state.
RunParts set_up(const Scene& scene, const SharedCuts& cuts, const MpiContext& mpi, SolverState& state,
                RunReport& report) {
  RunParts run;
  run.body = make_body(scene, cuts, report, 0.0, mpi);
  stop_if_interrupted("after the body was built (", run.body->node_count(), " nodes), before any step");
  run.mechanics = std::make_unique<MechanicalSystem>(*run.body, scene, report, mpi.ranks);
  run.probes = std::make_unique<ProbeSet>(scene, *run.mechanics);
  run.stepper = make_stepper(*run.mechanics, stepper_settings(scene), report);
  RankCounts& parallel = report.parallel;
  parallel.memory.after_body = peak_memory_mb();
  stop_if_interrupted("before the first assembly, with the body built");
  run.stepper->initialize(state);  // timed inside as assembly and factorize
  parallel.memory.after_initialization = peak_memory_mb();
  report.counts = {run.body->node_count(), run.body->dof_count(), run.body->element_count(),
                   run.body->mean_neighbors()};
  const RowShare& share = run.mechanics->dof_share();
  parallel.ranks = mpi.ranks.count;
  parallel.partitioned = share.partial;
  parallel.owned_rows = share.owned_end - share.owned_begin;
  parallel.touched_rows = share.partial ? static_cast<Index>(share.touched.size()) : run.mechanics->dof_count();
  return run;
}

/// Every rank's memory marks, in rank order (collective).
std::vector<MemoryMarks> memory_of_every_rank(const MemoryMarks& mine, const RankShare& ranks) {
  std::vector<MemoryMarks> marks;
  for (const std::vector<double>& v :
       values_of_every_rank({mine.after_body, mine.after_initialization, mine.at_end}, ranks))
    marks.push_back({v[0], v[1], v[2]});
  return marks;
}

/// The step loop: each step, then the cuts followed, then the output it is due.
void step(const Scene& scene, const SharedCuts& cuts, RunParts& run, SolverState& state, RunObserver& observer,
          RunReport& report, json& summary, const RunOptions& options) {
  CutFollower follower(scene, cuts, options.mpi);
  const int steps = run.stepper->step_count();
  const double dt = run.stepper->time_step(), start = now_seconds();
  const bool every_step = scene.solve.analysis == Analysis::static_analysis || scene.output.vtk_every <= 0;
  const int output_every = every_step ? 1 : scene.output.vtk_every;
  observer.reset_loads(run, state);
  for (int i = 1; i <= steps; ++i) {
    stop_if_interrupted("at step ", i, " of ", steps);
    observer.before_step(run, state);
    const double step_start = now_seconds();
    run.stepper->advance(state, dt);
    report.step_seconds.push_back(now_seconds() - step_start);
    report.solver.newton_iterations += run.stepper->last_iterations();
    observer.after_step(run, state);
    if (follower.follow(run, state, report)) {
      // Probes interpolate with the new shape functions or mesh (a probe on
      // a face now sees its own side only).
      run.probes = std::make_unique<ProbeSet>(scene, *run.mechanics);
      observer.reset_loads(run, state);
    }
    const bool last = i == steps;
    if (last || i % output_every == 0) observer.write(run, state, report.cut_update_seconds.size(), report);
    if (last) summary["probes"] = observer.final_probes(run, state);
    if (!options.quiet && (last || i % std::max(1, steps / 10) == 0))
      std::fprintf(stderr, "kerf: %s step %d/%d  t = %.6g  (%.3g s)\n", scene.name.c_str(), i, steps, state.t,
                   now_seconds() - start);
  }
}

}  // namespace

SharedCuts refuse_unrunnable(const Scene& scene) {
  validate(scene);
  return std::make_shared<const CutTimeline>(scene);
}

RunOutcome run_scene(const Scene& scene, const RunOptions& options) {
  const SharedCuts cuts = refuse_unrunnable(scene);
  RunOutcome outcome;
  outcome.directory = options.out_dir.empty() ? scene.output.dir : options.out_dir;
  const bool writes = options.writes_files();
  if (writes) std::filesystem::create_directories(outcome.directory);
  if (options.mpi.ranks.distributed()) wait_for_every_rank();  // they write pieces in it
  const std::string summary_path = outcome.directory + "/summary.json";
  Scene resolved = scene;
  resolved.output.dir = outcome.directory;
  json& summary = outcome.summary;
  summary = {{"kerf_version", version}, {"scene", scene_to_json(resolved)}, {"status", "running"}};
  if (writes) write_file_atomically(summary_path, summary_text(summary));

  RunReport& report = outcome.report;
  const InterruptScope interrupt;
  try {
    const ResourceEstimate estimate = estimate_and_guard(scene, options, outcome.directory, summary);
    const InterruptLastWords last_words(summary_saying_interrupted(writes ? summary_path : "", summary));
    const double start = now_seconds();
    SolverState state;
    std::optional<ProgressHeartbeat> heartbeat = announce_long_meshing(scene, options, estimate);
    RunParts run = set_up(scene, cuts, options.mpi, state, report);
    heartbeat.reset();
    report.setup_seconds = now_seconds() - start;
    RunObserver observer(scene, outcome.directory, cuts, *run.probes, options.mpi.ranks);
    observer.write(run, state, 0, report);
    const double loop_start = now_seconds();
    step(scene, cuts, run, state, observer, report, summary, options);
    report.solve_seconds = now_seconds() - loop_start;
    report.parallel.memory.at_end = peak_memory_mb();
    report.parallel.memory_by_rank = memory_of_every_rank(report.parallel.memory, options.mpi.ranks);
    if (const auto* figures = capability<DiscretizationFigures>(*run.body)) figures->add_figures(report.extras);
    if (options.keep_final_body) {
      run.stepper->complete_state(state);
      outcome.final_body = final_body(run, state);
    }
    write_report(report, summary);
    summary["status"] = "ok";
    if (writes) write_file_atomically(summary_path, summary_text(summary));
  } catch (const std::exception& e) {
    write_report(report, summary);
    write_failure(e, summary);
    if (options.mpi.ranks.distributed()) summary["error_rank"] = options.mpi.ranks.rank;
    if (writes) write_file_atomically(summary_path, summary_text(summary));
    // Failing alone, this rank leaves rank 0 waiting in a collective: it must say it itself.
    if (!writes && options.mpi.ranks.distributed())
      stop_every_rank(options.mpi.ranks, 1, e.what(), dynamic_cast<const SharedFailure*>(&e) != nullptr,
                      [&] { write_file_atomically(summary_path, summary_text(summary)); });
    throw;
  }
  return outcome;
}

}  // namespace kerf
