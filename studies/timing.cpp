// Timing study: the time of one step of each method and integrator at
// matching node counts, phase by phase, beside the paper's figures.
//
//   kerf study timing [--quick] [--out DIR]
//
// Two problems, both soft tissue (corotational, E = 3 kPa, nu = 0.3, rho =
// 1000 kg/m^3) clamped at the bottom and sagging under gravity:
//   block: the paper's small block (Figs. 14-15: 436 dofs, 105-125 FPS): a
//          3 x 5 x 5 cm block with nodes 1 cm apart, 144 nodes (432 dofs);
//   cube:  the paper's ~6000-node model: a 10 cm cube, 18^3 = 5 832 lattice
//          nodes (FEM: tet4 of the same edge length, a similar node count).
// Configurations: FEM tet4 with implicit Euler at 10 ms (the paper's SOFA
// baseline) and with central differences at 0.9 of its critical step; nodal
// integration with central differences at 1 ms (the paper's method) and with
// implicit Euler at 10 ms; EFG with implicit Euler at 10 ms. Implicit steps
// make one linearised solve, as SOFA's EulerImplicitSolver does. Each runs a fixed
// number of steps; the median step and the phases (assembly, factorize,
// solve) per step are read from the run's record. The paper's figures:
// FEM 195 ms a step, meshless 20.11 ms a step, the block at 125 FPS (8 ms).
// Speed is measured here, never asserted; the claims checked are that every
// configuration ran, that its phases were timed (explicit steps: the force
// evaluation, "assembly") and that they fit inside its step time.
#include <cmath>

#include "studies/study_scenes.h"
#include "studies/study_support.h"

namespace kerf {
namespace {

struct Problem {
  std::string name;
  double x, y, z;  // box edges (m)
  double spacing;  // m
};

struct Configuration {
  std::string label;
  Method method;
  Integrator integrator;
  double dt;  // s; 0: 0.9 of the critical step
};

Scene scene_of(const Problem& p, const Configuration& c, double dt, int steps) {
  using namespace study_scene;
  Scene scene = box_body("timing", Vec3(0, 0, 0), Vec3(p.x, p.y, p.z));
  scene.material = material(MaterialModel::corotational, 3000.0, 0.3, 1000.0, 4.0);
  scene.discretization.method = c.method;
  scene.discretization.fem.size = p.spacing;
  scene.discretization.meshless.spacing = p.spacing;
  scene.discretization.meshless.support = 2.3;
  scene.boundary = {held(2, 0.0)};
  scene.gravity = Vec3(0, 0, -9.81);
  scene.solve = implicit_steps(dt, steps);
  scene.solve.integrator = c.integrator;
  return scene;
}

const std::vector<Configuration>& configurations() {
  static const std::vector<Configuration> all{
      {"fem_tet4_implicit_euler", Method::fem, Integrator::implicit_euler, 0.01},
      {"fem_tet4_central_difference", Method::fem, Integrator::central_difference, 0.0},
      {"nodal_central_difference", Method::nodal, Integrator::central_difference, 0.001},
      {"nodal_implicit_euler", Method::nodal, Integrator::implicit_euler, 0.01},
      {"efg_implicit_euler", Method::efg, Integrator::implicit_euler, 0.01},
  };
  return all;
}

/// One configuration on one problem (explicit FEM first probes its critical
/// step with one tiny step): its point and its CSV row.
Json run_configuration(StudyRunner& runner, CsvTable& table, const Problem& p, const Configuration& c, bool quick) {
  const bool is_explicit = c.integrator == Integrator::central_difference;
  const int steps = is_explicit ? (quick ? 50 : 1000) : (quick ? 5 : 20);
  double dt = c.dt;
  if (dt == 0.0) {
    const RunRecord probe = runner.run(p.name + "_" + c.label + "_critical_step", scene_of(p, c, 1e-7, 1));
    dt = probe.ok() ? 0.9 * probe.report.solver.critical_dt_s.value() : 1e-4;
  }
  const RunRecord run = runner.run(p.name + "_" + c.label, scene_of(p, c, dt, steps));
  Json point = {{"problem", p.name}, {"configuration", c.label}};
  if (!run.ok()) {
    point["status"] = run.error;
    table.row({p.name, c.label, Json(), Json(), dt, steps, Json(), Json(), Json(), Json(), Json(), Json(), Json(),
               "error"});
    return point;
  }
  const double median = run.step_ms.median_ms;
  point.update({{"nodes", run.report.counts.nodes}, {"dofs", run.report.counts.dofs}, {"dt_s", dt},
                {"steps", steps}, {"step_median_ms", median}, {"step_mean_ms", run.step_ms.mean_ms},
                {"assembly_ms", phase_ms_per_step(run, Phase::assembly, steps)},
                {"factorize_ms", phase_ms_per_step(run, Phase::factorize, steps)},
                {"solve_ms", phase_ms_per_step(run, Phase::solve, steps)},
                {"setup_s", run.report.setup_seconds}, {"fps", 1e3 / median}, {"status", "ok"}});
  table.row({p.name, c.label, point["nodes"], point["dofs"], dt, steps, median, point["step_mean_ms"],
             point["assembly_ms"], point["factorize_ms"], point["solve_ms"], point["setup_s"], point["fps"], "ok"});
  runner.say(p.name + " " + c.label + ": " + std::to_string(median) + " ms a step (" + point["nodes"].dump() +
             " nodes)");
  return point;
}

void check_timing_claims(const Json& points) {
  for (const Json& p : points) {
    const std::string name = p["problem"].get<std::string>() + " " + p["configuration"].get<std::string>();
    check_claim(p["status"] == "ok", name + " ran (" + p["status"].get<std::string>() + ")");
    const double phases = p["assembly_ms"].get<double>() + p["factorize_ms"].get<double>() +
                          p["solve_ms"].get<double>();
    check_claim(phases > 0.0, name + ": its phases were timed");
    check_claim(phases <= 1.1 * p["step_mean_ms"].get<double>() + 0.01,
                name + ": the phases per step (" + std::to_string(phases) + " ms) fit in the mean step");
  }
}

}  // namespace

void timing_study(const StudyOptions& options) {
  // 1. Problems and configurations.
  std::vector<Problem> problems{{"block", 0.03, 0.05, 0.05, 0.01}};
  if (!options.quick) problems.push_back({"cube", 0.1, 0.1, 0.1, 0.1 / 17});
  int planned = 0;
  for (std::size_t i = 0; i < problems.size(); ++i)
    for (const Configuration& c : configurations()) planned += c.dt == 0.0 ? 2 : 1;
  StudyRunner runner("timing", options, planned);

  // 2. Run each.
  CsvTable table(runner.out_dir() + "/timing.csv",
                 {"problem", "configuration", "nodes", "dofs", "dt_s", "steps", "step_median_ms", "step_mean_ms",
                  "assembly_ms", "factorize_ms", "solve_ms", "setup_s", "fps", "status"});
  Json points = Json::array();
  for (const Problem& p : problems)
    for (const Configuration& c : configurations()) points.push_back(run_configuration(runner, table, p, c, options.quick));

  // 3. Write, with the paper's figures beside ours, and plot.
  StudyResult result("timing", options.quick, {"timing.png"});
  for (const Json& p : points)
    if (p["status"] == "ok")
      result.headline(p["problem"].get<std::string>() + " " + p["configuration"].get<std::string>() + " step (" +
                          p["nodes"].dump() + " nodes)",
                      p["step_median_ms"], "ms");
  result["paper"] = {{"fem_ms_per_step", 195.0}, {"meshless_ms_per_step", 20.11}, {"block_fps", 125.0},
                     {"source", "paper section 4 and Fig. 14: SOFA on a 2.67 GHz Core i5"}};
  result["points"] = points;
  result.write(runner.out_dir());
  plot("timing", runner.out_dir());

  // 4. The claims: every configuration ran, its phases were timed and fit in its steps.
  check_timing_claims(points);
}

}  // namespace kerf
