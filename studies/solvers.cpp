// Solvers study: which linear solver an FEM implicit step should use, by size.
//
//   kerf study solvers [--quick] [--out DIR]
//
// The timing study's cube (a 10 cm cube of corotational soft tissue, E = 3
// kPa, nu = 0.3, clamped at the bottom, sagging under gravity; implicit Euler
// at 10 ms, one linearised solve a step as SOFA does) meshed with tet4 at
// three sizes, about 6 000, 50 000 and 200 000 nodes (quick: about 1 000),
// each step solved by every linear solver to the same relative tolerance:
//   cholmod      CG preconditioned by the Cholesky factor of an earlier step's
//                matrix (refactorized when CG stalls: kerf's default);
//   gamg         PETSc CG + GAMG, the hierarchy rebuilt every step;
//   gamg_reuse   the same keeping the first step's hierarchy;
//   cg           Eigen CG with a diagonal preconditioner.
// Read from each run's record: the median and the largest step (the first
// holds the factorization or the hierarchy), phases per step, linear
// iterations. Speed is measured here, never asserted; the claims checked are
// that every point ran and that all solvers give the same sag (the solve is
// the only thing that differs).
#include <algorithm>
#include <cmath>

#include "studies/study_scenes.h"
#include "studies/study_support.h"

namespace kerf {
namespace {

struct Size {
  std::string label;
  double spacing;  // tet4 mesh size (m)
  int steps;
};

struct Solver {
  std::string label;
  LinearSolverKind linear_solver;
  std::string petsc;
};

Scene scene_of(const Size& size, const Solver& solver) {
  return study_scene::implicit_cube("solvers", size.spacing, size.steps, solver.linear_solver, solver.petsc, "top");
}

/// One solver at one size: its point and its CSV row.
Json run_solver(StudyRunner& runner, CsvTable& table, const Size& size, const Solver& solver) {
  const RunRecord run = runner.run(size.label + "_" + solver.label, scene_of(size, solver));
  Json point = {{"size", size.label}, {"solver", solver.label}};
  if (!run.ok()) {
    point["status"] = run.error;
    table.row({size.label, solver.label, Json(), Json(), size.steps, Json(), Json(), Json(), Json(), Json(), Json(),
               Json(), Json(), "error"});
    return point;
  }
  const SolverCounters& counters = run.report.solver;
  const double iterations =
      (static_cast<double>(counters.linear_iterations) + static_cast<double>(counters.pcg_iterations)) / size.steps;
  point.update({{"nodes", run.report.counts.nodes},
                {"dofs", run.report.counts.dofs},
                {"steps", size.steps},
                {"step_median_ms", run.step_ms.median_ms},
                {"step_max_ms", run.step_ms.max_ms},
                {"assembly_ms", phase_ms_per_step(run, Phase::assembly, size.steps)},
                {"factorize_ms", phase_ms_per_step(run, Phase::factorize, size.steps)},
                {"solve_ms", phase_ms_per_step(run, Phase::solve, size.steps)},
                {"linear_iterations_per_step", iterations},
                {"setup_s", run.report.setup_seconds},
                {"top_z_m", run.probe("top", 2)},
                {"status", "ok"}});
  table.row({size.label, solver.label, point["nodes"], point["dofs"], size.steps, point["step_median_ms"],
             point["step_max_ms"], point["assembly_ms"], point["factorize_ms"], point["solve_ms"], iterations,
             point["setup_s"], point["top_z_m"], "ok"});
  runner.say(size.label + " " + solver.label + ": median step " + point["step_median_ms"].dump() + " ms");
  return point;
}

/// solvers.json: every point, and the fastest solver at each size.
void write_results(const StudyRunner& runner, bool quick, const std::vector<Size>& sizes, const Json& points) {
  Json fastest = Json::object();
  for (const Size& size : sizes) {
    const Json* best = nullptr;
    for (const Json& p : points)
      if (p["size"] == size.label && p["status"] == "ok" &&
          (!best || p["step_median_ms"].get<double>() < (*best)["step_median_ms"].get<double>()))
        best = &p;
    if (best) fastest[size.label] = (*best)["solver"];
  }
  StudyResult result("solvers", quick, {"solvers.png"});
  for (const Json& p : points)
    if (p["status"] == "ok")
      result.headline(p["solver"].get<std::string>() + " median step (" + p["nodes"].dump() + " nodes)",
                      p["step_median_ms"], "ms");
  result["fastest_by_median_step"] = fastest;
  result["points"] = points;
  result.write(runner.out_dir());
}

/// Every point ran, and every solver gives the sag of the first.
void check_solvers_claims(const std::vector<Size>& sizes, const Json& points) {
  for (const Size& size : sizes) {
    const Json* reference = nullptr;
    for (const Json& p : points) {
      if (p["size"] != size.label) continue;
      const std::string name = size.label + " " + p["solver"].get<std::string>();
      check_claim(p["status"] == "ok", name + " ran (" + p["status"].get<std::string>() + ")");
      if (!reference) reference = &p;
      const double z = p["top_z_m"].get<double>(), z0 = (*reference)["top_z_m"].get<double>();
      check_claim(std::abs(z - z0) <= 1e-5 * std::abs(z0),
                  name + ": its sag " + std::to_string(z) + " m is the " + (*reference)["solver"].get<std::string>() +
                      " run's " + std::to_string(z0) + " m to 1e-5");
    }
  }
}

}  // namespace

void solvers_study(const StudyOptions& options) {
  // 1. Sizes and solvers.
  std::vector<Size> sizes;
  if (options.quick)
    sizes = {{"1k", 0.011, 3}};
  else
    sizes = {{"6k", 0.0054, 5}, {"50k", 0.0027, 5}, {"200k", 0.0017, 3}};
  const std::vector<Solver> solvers{
      {"cholmod", LinearSolverKind::cholmod, ""},
      {"gamg", LinearSolverKind::petsc, "-ksp_type cg -pc_type gamg"},
      {"gamg_reuse", LinearSolverKind::petsc, "-ksp_type cg -pc_type gamg -ksp_reuse_preconditioner"},
      {"cg", LinearSolverKind::cg, ""},
  };
  StudyRunner runner("solvers", options, static_cast<int>(sizes.size() * solvers.size()));

  // 2. Run each.
  CsvTable table(runner.out_dir() + "/solvers.csv",
                 {"size", "solver", "nodes", "dofs", "steps", "step_median_ms", "step_max_ms", "assembly_ms",
                  "factorize_ms", "solve_ms", "linear_iterations_per_step", "setup_s", "top_z_m", "status"});
  Json points = Json::array();
  for (const Size& size : sizes)
    for (const Solver& solver : solvers) points.push_back(run_solver(runner, table, size, solver));

  // 3. The fastest solver at each size, written and plotted; 4. the claims.
  write_results(runner, options.quick, sizes, points);
  plot("solvers", runner.out_dir());
  check_solvers_claims(sizes, points);
}

}  // namespace kerf
