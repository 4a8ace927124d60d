// Scaling study: the same scene on 1 to 4 MPI ranks, phase by phase.
//
//   kerf study scaling [--quick] [--out DIR]
//
// Each point is a separate `kerf run` under mpirun (1 rank: no mpirun), one
// OpenMP thread a rank, so that ranks, not threads, share the cores; the
// 1-rank run with as many threads as cores is measured beside them (what one
// process does on the whole machine). Ranks past the cores oversubscribe
// them: their memory counts, not their time. The problems:
//   static_tet10   strong scaling: the cantilever (10 x 2 x 2 cm, linear,
//                  under its weight) in tet10, about 500 000 dofs (quick: 10 000);
//   static_tet10_lean  the same with kerf's own PETSc options under mpirun
//                  (solve.petsc left out: GAMG's memory options), for the
//                  memory a rank against 1/N;
//   implicit_tet4  strong scaling: the solvers study's corotational cube,
//                  implicit Euler, one linearised solve a step, about 300 000
//                  dofs (quick: 3 000), 3 steps;
//   explicit_tet4  strong scaling: the same cube by central differences,
//                  about 150 000 dofs (quick: 3 000), 200 steps (quick: 20);
//   explicit_nodal the cube by nodal integration and central differences,
//                  about 200 000 dofs (quick: 4 000), 200 steps (quick: 20);
//   static_efg     the cantilever by EFG, about 18 000 dofs (quick: 2 800);
//   weak_tet10     weak scaling: the cantilever with about 200 000 dofs a
//                  rank (skipped in quick mode).
// Every linear solve is PETSc CG + GAMG with the rigid-body near-null space,
// to a relative residual of 1e-8. Read from each run: the phases (setup,
// assembly, factorize = the preconditioner's set-up, solve, output), the
// time-stepping loop's, the launch's wall time and every rank's peak memory. Speed is measured here, never
// asserted; the claims checked are that every point ran and that the ranks
// give the 1-rank answer to the solver's tolerance.
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <thread>

#include "studies/study_scenes.h"
#include "studies/study_support.h"

namespace kerf {
namespace {

/// Which launches a problem takes beside 1, 2 and 3 ranks of one thread.
enum class Launches {
  all,         // also 4 ranks (memory) and one rank of every core
  memory,      // also 4 ranks: a memory series, no threads
  three_ranks  // weak scaling: its own mesh a launch, up to 3 ranks
};

struct Problem {
  std::string label;
  Launches launches;
  int steps = 1;  // time steps of a dynamic problem
  Scene (*scene)(double size, int steps);
  double size;  // mesh size (or node spacing) at one rank (m); weak scaling shrinks it with the ranks
  bool weak() const { return launches == Launches::three_ranks; }
};

/// PETSc's own GAMG defaults on any number of ranks, written out (so a run
/// on several does not add kerf's memory options, petsc_rank_options): the
/// study compares speed with one solver; the memory options are measured
/// beside it (results/scaling.md).
constexpr const char* same_gamg_on_every_rank = "-ksp_type cg -pc_type gamg -pc_gamg_agg_nsmooths 1";

Scene cantilever(double size, int /*steps: static*/) {
  using namespace study_scene;
  Scene scene = box_body("scaling", Vec3(0, 0, 0), Vec3(0.1, 0.02, 0.02));
  scene.material = material(MaterialModel::linear, 1.0e6, 0.3);
  scene.discretization.fem.element = ElementType::tet10;
  scene.discretization.fem.size = size;
  scene.boundary = {held(0, 0.0)};
  scene.gravity = Vec3(0, 0, -9.81);
  scene.solve.linear_solver = LinearSolverKind::petsc;
  scene.solve.petsc = same_gamg_on_every_rank;
  scene.solve.petsc_written = true;
  scene.solve.linear_tolerance = 1.0e-8;
  scene.output.probes = {displacement_probe("probe", Vec3(0.1, 0.01, 0.01))};
  return scene;
}

/// The cantilever with the PETSc options kerf chooses itself on several ranks (solvers/linear_solver.h).
Scene lean_cantilever(double size, int steps) {
  Scene scene = cantilever(size, steps);
  scene.solve.petsc = SolveOptions{}.petsc;
  scene.solve.petsc_written = false;
  return scene;
}

/// `scene` by the meshless `method` on a lattice of `spacing` (m).
Scene on_lattice(Scene scene, Method method, double spacing) {
  scene.discretization.method = method;
  scene.discretization.meshless.spacing = spacing;
  return scene;
}

Scene efg_cantilever(double spacing, int steps) { return on_lattice(cantilever(spacing, steps), Method::efg, spacing); }

Scene corotational_cube(double size, int steps) {
  return study_scene::implicit_cube("scaling", size, steps, LinearSolverKind::petsc, same_gamg_on_every_rank, "probe");
}

/// The corotational cube by central differences, steps of 0.4 ms: under the
/// critical step of the finest mesh run (0.49 ms at 2.5 mm).
Scene explicit_cube(double size, int steps) {
  Scene scene = corotational_cube(size, 1);
  scene.solve.integrator = Integrator::central_difference;
  scene.solve.dt = 0.0004;
  scene.solve.duration = 0.0004 * steps;
  return scene;
}

Scene explicit_nodal_cube(double spacing, int steps) {
  return on_lattice(explicit_cube(spacing, steps), Method::nodal, spacing);
}

const Phase phases[] = {Phase::setup, Phase::assembly, Phase::factorize, Phase::solve, Phase::output};

std::string key_of(Phase phase) { return std::string(phase_names[static_cast<int>(phase)]) + "_s"; }

/// The largest of every rank's memory mark `mark`.
double largest(const std::vector<MemoryMarks>& ranks, double MemoryMarks::*mark) {
  double most = 0.0;
  for (const MemoryMarks& m : ranks) most = std::max(most, m.*mark);
  return most;
}

/// One point's row: its figures from the run's record.
Json point_of(const Problem& problem, int ranks, int threads, const LaunchedRun& launched) {
  Json point = {{"problem", problem.label}, {"ranks", ranks}, {"threads", threads}};
  const RunRecord& run = launched.run;
  if (!run.ok()) {
    point["status"] = run.error;
    return point;
  }
  for (const Phase phase : phases) point[key_of(phase)] = run.report.phases.seconds(phase);
  const std::vector<MemoryMarks>& memory = run.report.parallel.memory_by_rank;
  point.update({{"status", "ok"},
                {"dofs", run.report.counts.dofs},
                {"wall_s", launched.wall_s},
                {"loop_s", run.report.solve_seconds},
                {"partitioned", run.report.parallel.partitioned},
                {"rank0_touched_rows", run.report.parallel.touched_rows},
                {"rank0_peak_memory_mb", run.peak_memory_mb},
                {"largest_rank_peak_memory_mb", largest(memory, &MemoryMarks::at_end)},
                {"largest_rank_memory_after_body_mb", largest(memory, &MemoryMarks::after_body)},
                {"linear_iterations", run.report.solver.linear_iterations},
                {"probe_z_m", run.probe("probe", 2)}});
  return point;
}

/// The problem's point on one rank of one thread, or null when it failed.
const Json* one_rank_point(const Json& points, const std::string& problem) {
  for (const Json& p : points)
    if (p["problem"] == problem && p["ranks"] == 1 && p["threads"] == 1 && p["status"] == "ok") return &p;
  return nullptr;
}

double phase_sum(const Json& point, std::initializer_list<const char*> names) {
  double total = 0.0;
  for (const char* name : names) total += point[std::string(name) + "_s"].get<double>();
  return total;
}

/// Every other launch's speed-ups over one rank of one thread, phase by phase (strong scaling).
Json strong_speedups(const std::vector<Problem>& problems, const Json& points) {
  Json speedups = Json::array();
  for (const Problem& problem : problems) {
    const Json* one = problem.weak() ? nullptr : one_rank_point(points, problem.label);
    if (!one) continue;
    for (const Json& p : points) {
      if (p["problem"] != problem.label || p["status"] != "ok" || &p == one) continue;
      Json s = {{"problem", problem.label}, {"ranks", p["ranks"]}, {"threads", p["threads"]}};
      for (const Phase phase : phases) {
        const char* name = phase_names[static_cast<int>(phase)];
        const double mine = phase_sum(p, {name});
        s[name] = mine > 0.0 ? phase_sum(*one, {name}) / mine : 0.0;
      }
      s["assembly_factorize_solve"] = phase_sum(*one, {"assembly", "factorize", "solve"}) /
                                      phase_sum(p, {"assembly", "factorize", "solve"});
      s["loop"] = phase_sum(*one, {"loop"}) / phase_sum(p, {"loop"});
      s["wall"] = phase_sum(*one, {"wall"}) / phase_sum(p, {"wall"});
      speedups.push_back(s);
    }
  }
  return speedups;
}

const char* const figure_columns[] = {"rank0_peak_memory_mb", "largest_rank_peak_memory_mb",
                                      "largest_rank_memory_after_body_mb", "linear_iterations", "probe_z_m"};

/// A point's CSV row (empty cells where it failed).
std::vector<Json> row_of(const Json& point) {
  std::vector<Json> row{point["problem"], point["ranks"], point["threads"], point.value("dofs", Json()),
                        point.value("wall_s", Json()), point.value("loop_s", Json())};
  for (const Phase phase : phases) row.push_back(point.value(key_of(phase), Json()));
  for (const char* c : figure_columns) row.push_back(point.value(c, Json()));
  row.push_back(point["status"] == "ok" ? "ok" : "error");
  return row;
}

void check_scaling_claims(const std::vector<Problem>& problems, const Json& points) {
  for (const Json& p : points)
    check_claim(p["status"] == "ok", p["problem"].get<std::string>() + " on " + p["ranks"].dump() + " ranks of " +
                                         p["threads"].dump() + " threads ran (" + p["status"].dump() + ")");
  for (const Problem& problem : problems) {
    if (problem.weak()) continue;  // each launch has its own mesh
    const Json* one = one_rank_point(points, problem.label);
    for (const Json& p : points) {
      if (p["problem"] != problem.label) continue;
      const double a = (*one)["probe_z_m"].get<double>(), b = p["probe_z_m"].get<double>();
      check_claim(std::abs(a - b) <= 1e-6 * std::abs(a),
                  problem.label + " on " + p["ranks"].dump() + " ranks: probe " + std::to_string(b) +
                      " m against 1 rank's " + std::to_string(a) + " m (to 1e-6 relative)");
    }
  }
}

}  // namespace

void scaling_study(const StudyOptions& options) {
  // 1. The problems and the launches: 1 to 4 ranks of one thread, and one rank of every core.
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<Problem> problems;
  if (options.quick)
    problems = {{"static_tet10", Launches::all, 1, cantilever, 0.005},
                {"static_tet10_lean", Launches::memory, 1, lean_cantilever, 0.005},
                {"implicit_tet4", Launches::all, 3, corotational_cube, 0.011},
                {"explicit_tet4", Launches::all, 20, explicit_cube, 0.011},
                {"explicit_nodal", Launches::all, 20, explicit_nodal_cube, 0.01},
                {"static_efg", Launches::all, 1, efg_cantilever, 0.004}};
  else
    problems = {{"static_tet10", Launches::all, 1, cantilever, 0.00116},
                {"static_tet10_lean", Launches::memory, 1, lean_cantilever, 0.00116},
                {"implicit_tet4", Launches::all, 3, corotational_cube, 0.002},
                {"explicit_tet4", Launches::all, 200, explicit_cube, 0.0025},
                {"explicit_nodal", Launches::all, 200, explicit_nodal_cube, 0.0025},
                {"static_efg", Launches::all, 1, efg_cantilever, 0.002},
                {"weak_tet10", Launches::three_ranks, 1, cantilever, 0.0016}};
  struct Launch {
    int ranks, threads;
  };
  auto launches_of = [cores](const Problem& problem) {
    std::vector<Launch> launches{{1, 1}, {2, 1}, {3, 1}};
    if (problem.launches != Launches::three_ranks) launches.push_back({4, 1});
    if (problem.launches == Launches::all && cores > 1) launches.push_back({1, cores});
    return launches;
  };
  int planned = 0;
  for (const Problem& problem : problems) planned += static_cast<int>(launches_of(problem).size());
  StudyRunner runner("scaling", options, planned);

  // 2. Run each.
  std::vector<std::string> columns{"problem", "ranks", "threads", "dofs", "wall_s", "loop_s"};
  for (const Phase phase : phases) columns.push_back(key_of(phase));
  for (const char* c : figure_columns) columns.push_back(c);
  columns.push_back("status");
  CsvTable table(runner.out_dir() + "/scaling.csv", columns);
  Json points = Json::array();
  for (const Problem& problem : problems)
    for (const Launch& launch : launches_of(problem)) {
      const double size = problem.weak() ? problem.size / std::cbrt(static_cast<double>(launch.ranks)) : problem.size;
      const std::string label =
          problem.label + "_" + std::to_string(launch.ranks) + "x" + std::to_string(launch.threads);
      const Json point = point_of(problem, launch.ranks, launch.threads,
                                  runner.run_on_ranks(label, problem.scene(size, problem.steps), launch.ranks, launch.threads));
      table.row(row_of(point));
      points.push_back(point);
    }

  // 3. Speed-ups against one rank of one thread, written and plotted.
  StudyResult result("scaling", options.quick, {"scaling.png"});
  result["cores"] = cores;
  result["speedups"] = strong_speedups(problems, points);
  result["points"] = points;
  result.write(runner.out_dir());
  plot("scaling", runner.out_dir());

  // 4. The claims: every point ran, and every launch gives the 1-rank answer to the solver's tolerance.
  check_scaling_claims(problems, points);
}

}  // namespace kerf
