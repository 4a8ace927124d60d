#include "app/session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <utility>

#include "app/cut_follower.h"
#include "app/resource_estimate.h"
#include "app/run_observer.h"
#include "app/run_parts.h"
#include "app/summary_json.h"
#include "core/check.h"
#include "core/interrupt.h"
#include "core/peak_memory.h"
#include "core/progress_heartbeat.h"
#include "core/timer.h"
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
  if (options.quiet || !estimate.gmsh_meshes || estimate.mesh_cells <= 1e6) return std::nullopt;
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

/// The body as ParaView gets it (at the end of the run, or now).
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

/// "[x y z] to [x y z]" (m).
std::string text_of(const Box& box) {
  std::ostringstream text;
  text << "[" << box.min.transpose() << "] to [" << box.max.transpose() << "]";
  return text.str();
}

/// The box around the pieces `added` makes with the cut's vertices so far (`fed`; corners a piece: 2 for a
/// polyline, 3 for a strip): the new vertices and the last corners - 1 before them. Empty (min > max) when
/// they make no piece yet.
Box box_of_new_pieces(std::span<const Vec3> fed, std::span<const Vec3> added, std::size_t corners) {
  Box box{Vec3::Constant(1e300), Vec3::Constant(-1e300)};
  if (fed.size() + added.size() < corners) return box;
  auto take = [&](const Vec3& v) { box.min = box.min.cwiseMin(v), box.max = box.max.cwiseMax(v); };
  std::for_each(fed.end() - static_cast<std::ptrdiff_t>(std::min(fed.size(), corners - 1)), fed.end(), take);
  std::for_each(added.begin(), added.end(), take);
  return box;
}

/// The box around a body's nodes (on every rank: the box around their pieces), a millionth of its size
/// wider. A cut splitting or remeshing the body keeps it. Collective.
Box box_of_body(const DiscreteBody& body, const RankShare& ranks) {
  Box box{Vec3::Constant(1e300), Vec3::Constant(-1e300)};
  for (Index n = 0; n < body.node_count(); ++n)
    box.min = box.min.cwiseMin(body.node_position(n)), box.max = box.max.cwiseMax(body.node_position(n));
  if (ranks.distributed())
    for (const std::vector<double>& r : values_of_every_rank(
             {box.min.x(), box.min.y(), box.min.z(), box.max.x(), box.max.y(), box.max.z()}, ranks))
      box.min = box.min.cwiseMin(Vec3(r[0], r[1], r[2])), box.max = box.max.cwiseMax(Vec3(r[3], r[4], r[5]));
  const Vec3 margin = Vec3::Constant(1e-6 * (box.max - box.min).norm());
  return {box.min - margin, box.max + margin};
}

/// Every rank's memory marks, in rank order (collective).
std::vector<MemoryMarks> memory_of_every_rank(const MemoryMarks& mine, const RankShare& ranks) {
  std::vector<MemoryMarks> marks;
  for (const std::vector<double>& v :
       values_of_every_rank({mine.after_body, mine.after_initialization, mine.at_end}, ranks))
    marks.push_back({v[0], v[1], v[2]});
  return marks;
}

}  // namespace

std::shared_ptr<CutTimeline> refuse_unrunnable(const Scene& scene) {
  validate(scene);
  return std::make_shared<CutTimeline>(scene);
}

/// What an open session holds. Its members are made in this order (the
/// scene first: the parts refer to it).
struct Session::Run {
  Run(const Scene& scene, const RunOptions& options);
  void open();
  void step();
  RunOutcome finish();
  /// Runs `work`; on failure, the summary says "error" with the message (every
  /// file already written kept) and the failure goes on to the caller: on an
  /// MPI rank that writes no files, by stopping every rank (rank 0 is then
  /// waiting for it in a collective call).
  template <class Work>
  decltype(auto) guarded(Work&& work);
  void write_summary() {
    if (options.writes_files()) write_file_atomically(summary_path, summary_text(outcome.summary));
  }
  /// The caller's errors, refused without touching the summary: a call on a
  /// finished or failed session, a hand on a static run, a sphere not in the scene.
  void refuse_if_closed(const char* what) const;
  void refuse_unless_dynamic(const char* what) const;
  ContactTerm& contact_sphere(Index sphere, const char* what) const;

  const Scene scene;
  const RunOptions options;
  const std::shared_ptr<CutTimeline> timeline;  // extend_cut's; the run's parts read it as `cuts`
  const SharedCuts cuts;
  RunOutcome outcome;
  std::string summary_path;
  std::optional<InterruptLastWords> last_words;
  SolverState state;
  RunParts parts;
  std::optional<RunObserver> observer;
  std::optional<CutFollower> follower;
  int output_every = 1;
  int taken = 0;       // steps
  int written_at = 0;  // the step whose output was written last
  Vector body_u, body_v;  // the body's part of the state (a contact sphere's dofs follow it)
  Box body_box;           // around the body's nodes: a blade off it is refused
  bool finished = false, failed = false;
};

Session::Run::Run(const Scene& scene_in, const RunOptions& options_in)
    : scene(scene_in), options(options_in), timeline(refuse_unrunnable(scene)), cuts(timeline) {
  outcome.directory = options.out_dir.empty() ? scene.output.dir : options.out_dir;
  if (options.writes_files()) std::filesystem::create_directories(outcome.directory);
  if (options.mpi.ranks.distributed()) wait_for_every_rank();  // they write pieces in it
  summary_path = outcome.directory + "/summary.json";
  Scene resolved = scene;
  resolved.output.dir = outcome.directory;
  outcome.summary = {{"kerf_version", version}, {"scene", scene_to_json(resolved)}, {"status", "running"}};
  write_summary();
}

template <class Work>
decltype(auto) Session::Run::guarded(Work&& work) {
  KERF_CHECK(!failed, "this session failed earlier: open a new one");
  try {
    return work();
  } catch (const std::exception& e) {
    failed = true;
    json& summary = outcome.summary;
    write_report(outcome.report, summary);
    write_failure(e, summary);
    if (options.mpi.ranks.distributed()) summary["error_rank"] = options.mpi.ranks.rank;
    write_summary();
    if (!options.writes_files() && options.mpi.ranks.distributed())
      stop_every_rank(options.mpi.ranks, 1, e.what(), dynamic_cast<const SharedFailure*>(&e) != nullptr,
                      [&] { write_file_atomically(summary_path, summary_text(summary)); });
    throw;
  }
}

void Session::Run::open() {
  RunReport& report = outcome.report;
  const ResourceEstimate estimate = estimate_and_guard(scene, options, outcome.directory, outcome.summary);
  last_words.emplace(summary_saying_interrupted(options.writes_files() ? summary_path : "", outcome.summary));
  const double start = now_seconds();
  std::optional<ProgressHeartbeat> heartbeat = announce_long_meshing(scene, options, estimate);
  parts = set_up(scene, cuts, options.mpi, state, report);
  body_box = box_of_body(*parts.body, options.mpi.ranks);
  heartbeat.reset();
  report.setup_seconds = now_seconds() - start;
  observer.emplace(scene, outcome.directory, cuts, *parts.probes, options.mpi.ranks);
  follower.emplace(scene, cuts, options.mpi);
  observer->write(parts, state, 0, report);
  const bool every_step = scene.solve.analysis == Analysis::static_analysis || scene.output.vtk_every <= 0;
  output_every = every_step ? 1 : scene.output.vtk_every;
  observer->reset_loads(parts, state);
}

void Session::Run::step() {
  RunReport& report = outcome.report;
  const int steps = parts.stepper->step_count(), i = taken + 1;
  const double start = now_seconds();
  stop_if_interrupted("at step ", i, " of ", steps);
  observer->before_step(parts, state);
  parts.stepper->advance(state, parts.stepper->time_step());
  report.step_seconds.push_back(now_seconds() - start);
  report.solver.newton_iterations += parts.stepper->last_iterations();
  taken = i;
  observer->after_step(parts, state);
  if (follower->follow(parts, state, report)) {
    // Probes interpolate with the new shape functions or mesh (a probe on
    // a face now sees its own side only).
    parts.probes = std::make_unique<ProbeSet>(scene, *parts.mechanics);
    observer->reset_loads(parts, state);
  }
  if (i == steps || i % output_every == 0) {
    observer->write(parts, state, report.cut_update_seconds.size(), report);
    written_at = i;
  }
  report.solve_seconds += now_seconds() - start;
  if (!options.quiet && (i == steps || i % std::max(1, steps / 10) == 0))
    std::fprintf(stderr, "kerf: %s step %d/%d  t = %.6g  (%.3g s)\n", scene.name.c_str(), i, steps, state.t,
                 report.solve_seconds);
}

RunOutcome Session::Run::finish() {
  RunReport& report = outcome.report;
  if (written_at != taken) {  // ended early: the files end where the run stopped
    observer->write(parts, state, report.cut_update_seconds.size(), report);
    written_at = taken;
  }
  outcome.summary["probes"] = observer->final_probes(parts, state);
  report.parallel.memory.at_end = peak_memory_mb();
  report.parallel.memory_by_rank = memory_of_every_rank(report.parallel.memory, options.mpi.ranks);
  if (const auto* figures = capability<DiscretizationFigures>(*parts.body)) figures->add_figures(report.extras);
  if (options.keep_final_body) {
    parts.stepper->complete_state(state);
    outcome.final_body = final_body(parts, state);
  }
  write_report(report, outcome.summary);
  outcome.summary["status"] = "ok";
  write_summary();
  finished = true;
  return outcome;
}

Session::Session(const Scene& scene, const RunOptions& options) {
  auto run = std::make_unique<Run>(scene, options);
  run->guarded([&] { run->open(); });
  run_ = std::move(run);
}

Session::~Session() {
  if (!run_ || run_->finished || run_->failed) return;
  try {
    run_->guarded([&] { run_->finish(); });
  } catch (...) {  // a destructor must not throw: the summary says what failed
  }
}

void Session::step() {
  // A call out of turn is the caller's error, not the run's: the summary does not change.
  KERF_CHECK(!run_->finished, "this session is finished: open a new one to run again");
  KERF_CHECK(!done(), "the session took every step its scene asks for (", step_count(),
             "; solve.duration / solve.dt, or solve.load_steps): finish it");
  run_->guarded([&] { run_->step(); });
}

void Session::extend_cut(Index cut, std::span<const Vec3> vertices) {
  // A refused piece is the caller's error, not the run's: the cut and the summary stay as they were.
  run_->refuse_if_closed("extend_cut");
  KERF_CHECK(cut >= 0 && cut < run_->timeline->cut_count(), "cut ", cut, " does not exist: the scene has ",
             run_->timeline->cut_count(), " cut(s)");
  refuse_a_blade_outside(cut, vertices);
  run_->timeline->extend(cut, vertices, run_->state.t);
}

void Session::refuse_a_blade_outside(Index cut, std::span<const Vec3> vertices) const {
  // New pieces that lie wholly outside the body's box cut nothing: a blade moved off the body. (Inside the
  // box but outside a curved body is not refused: only what is certainly outside is.)
  const CutSurface& now = run_->timeline->surface(cut);
  const int dim = now.dimension;
  const Box pieces = box_of_new_pieces(now.vertices, vertices, dim == 2 ? 2 : 3);
  if ((pieces.min.array() > pieces.max.array()).any()) return;  // no piece yet: the blade's first position
  const Box& body = run_->body_box;
  bool apart = false;
  for (int a = 0; a < dim; ++a) apart |= pieces.max[a] < body.min[a] || pieces.min[a] > body.max[a];
  if (!apart) return;
  std::ostringstream where;
  for (const Vec3& v : vertices) where << " [" << v.transpose() << "]";
  throw Error(now.where + ": the blade's new position (" + where.str().substr(1) + ") leaves the cut's new " +
              "pieces wholly outside the body's box (theirs " + text_of(pieces) + ", the body's " + text_of(body) +
              "); expected a position that cuts into the body. The cut is kept as it was");
}

ContactTerm& Session::Run::contact_sphere(Index sphere, const char* what) const {
  ContactTerm* contact = parts.mechanics->contact();
  const Index spheres = contact ? contact->sphere_count() : 0;
  KERF_CHECK(sphere >= 0 && sphere < spheres, what, ": sphere ", sphere, " is not in the scene's 'contact' list, ",
             "which has ", spheres, " spheres");
  return *contact;
}

void Session::Run::refuse_if_closed(const char* what) const {
  KERF_CHECK(!finished && !failed, what, ": this session is ", failed ? "failed" : "finished", "; open a new one");
}

void Session::Run::refuse_unless_dynamic(const char* what) const {
  KERF_CHECK(scene.solve.analysis == Analysis::dynamic, scene.locate("solve.analysis").describe(), ": ", what,
             " acts between time steps; expected a dynamic run (a static run scales its loads by its load steps)");
}

ContactTerm& Session::sphere_in_hand(Index sphere, const char* what) {
  run_->refuse_if_closed(what);
  run_->refuse_unless_dynamic(what);
  return run_->contact_sphere(sphere, what);
}

void Session::move_sphere(Index sphere, const Vec3& displacement) {
  sphere_in_hand(sphere, "move_sphere").move_sphere(sphere, displacement);  // refused: the sphere as it was
  run_->guarded([&] { run_->parts.stepper->applied_changed(run_->state); });
}

void Session::push_sphere(Index sphere, const Vec3& force) {
  sphere_in_hand(sphere, "push_sphere").push_sphere(sphere, force);
  run_->guarded([&] { run_->parts.stepper->applied_changed(run_->state); });
}

void Session::scale_loads(double factor) {
  run_->refuse_if_closed("scale_loads");
  run_->refuse_unless_dynamic("scale_loads");
  KERF_CHECK(std::isfinite(factor), "scale_loads: the factor ", factor, " is not a finite number");
  run_->parts.mechanics->scale_loads(factor);
  run_->guarded([&] { run_->parts.stepper->applied_changed(run_->state); });
}

bool Session::done() const { return run_->taken >= run_->parts.stepper->step_count(); }
int Session::steps_taken() const { return run_->taken; }
bool Session::failed() const { return run_->failed; }
int Session::step_count() const { return run_->parts.stepper->step_count(); }
double Session::time() const { return run_->state.t; }
double Session::time_step() const { return run_->parts.stepper->time_step(); }
int Session::dofs_per_node() const { return run_->parts.body->dofs_per_node(); }
Index Session::node_count() const { return run_->parts.body->node_count(); }

const Vector& Session::displacement() {
  return run_->guarded([&]() -> const Vector& {
    run_->parts.stepper->complete_state(run_->state);
    return run_->parts.mechanics->body_part(run_->state.u, run_->body_u);
  });
}

const Vector& Session::velocity() {
  return run_->guarded([&]() -> const Vector& {
    run_->parts.stepper->complete_state(run_->state);
    return run_->parts.mechanics->body_part(run_->state.v, run_->body_v);
  });
}

nlohmann::ordered_json Session::probes() {
  return run_->guarded([&] { return run_->observer->probes_now(run_->parts, run_->state); });
}

Vec3 Session::contact_force(Index sphere) {
  const ContactTerm& contact = run_->contact_sphere(sphere, "contact_force");
  return run_->guarded([&] {
    run_->parts.stepper->complete_state(run_->state);
    return contact.reading(sphere, run_->state.u).force;
  });
}

BodySnapshot Session::snapshot() {
  return run_->guarded([&] {
    run_->parts.stepper->complete_state(run_->state);
    return *final_body(run_->parts, run_->state);
  });
}

RunOutcome Session::finish() {
  KERF_CHECK(!run_->finished, "this session is finished already");
  return run_->guarded([&] { return run_->finish(); });
}

}  // namespace kerf
