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
// solve) per step are read from the run's summary. The paper's figures:
// FEM 195 ms a step, meshless 20.11 ms a step, the block at 125 FPS (8 ms).
// Speed is measured here, never asserted; the claims checked are that every
// configuration ran, that its phases were timed (explicit steps: the force
// evaluation, "assembly") and that they fit inside its step time.
#include <cmath>
#include <sstream>

#include "studies/study_support.h"

namespace kerf {
namespace {

struct Problem {
  std::string name;
  double x, y, z;  // box edges (m)
  double spacing;  // m
};

struct Configuration {
  std::string label, method, integrator;
  double dt;  // s; 0: 0.9 of the critical step
};

std::string scene_text(const Problem& p, const Configuration& c, double dt, int steps) {
  std::ostringstream s;
  s.precision(12);
  s << "name: timing\n"
    << "domain: {box: {min: [0, 0, 0], max: [" << p.x << ", " << p.y << ", " << p.z << "]}}\n"
    << "material: {model: corotational, young: 3000.0, poisson: 0.3, density: 1000.0, damping: {mass: 4.0}}\n"
    << "discretization:\n"
    << "  method: " << c.method << "\n"
    << "  fem: {element: tet4, size: " << p.spacing << "}\n"
    << "  meshless: {spacing: " << p.spacing << ", support: 2.3}\n"
    << "boundary:\n"
    << "  - {select: {plane: {axis: z, at: 0}}, fix: [x, y, z]}\n"
    << "body_force: {gravity: [0, 0, -9.81]}\n"
    << "solve: {analysis: dynamic, integrator: " << c.integrator << ", dt: " << dt << ", duration: " << dt * steps
    << ", newton: {max_iterations: 1}}\n"
    << "output: {vtk: false}\n";
  return s.str();
}

}  // namespace

void timing_study(const StudyOptions& options) {
  // 1. Problems and configurations.
  std::vector<Problem> problems{{"block", 0.03, 0.05, 0.05, 0.01}};
  if (!options.quick) problems.push_back({"cube", 0.1, 0.1, 0.1, 0.1 / 17});
  const std::vector<Configuration> configurations{
      {"fem_tet4_implicit_euler", "fem", "implicit-euler", 0.01},
      {"fem_tet4_central_difference", "fem", "central-difference", 0.0},
      {"nodal_central_difference", "nodal", "central-difference", 0.001},
      {"nodal_implicit_euler", "nodal", "implicit-euler", 0.01},
      {"efg_implicit_euler", "efg", "implicit-euler", 0.01},
  };
  const int explicit_steps = options.quick ? 50 : 1000, implicit_steps = options.quick ? 5 : 20;
  int planned = 0;
  for (std::size_t i = 0; i < problems.size(); ++i)
    for (const Configuration& c : configurations) planned += c.dt == 0.0 ? 2 : 1;
  StudyRunner runner("timing", options, planned);

  // 2. Run each; explicit FEM first probes its critical step with one tiny step.
  CsvTable table(runner.out_dir() + "/timing.csv",
                 {"problem", "configuration", "nodes", "dofs", "dt_s", "steps", "step_median_ms", "step_mean_ms",
                  "assembly_ms", "factorize_ms", "solve_ms", "setup_s", "fps", "status"});
  Json points = Json::array();
  for (const Problem& p : problems) {
    for (const Configuration& c : configurations) {
      const bool is_explicit = c.integrator == "central-difference";
      const int steps = is_explicit ? explicit_steps : implicit_steps;
      double dt = c.dt;
      if (dt == 0.0) {
        const Json probe = runner.run(p.name + "_" + c.label + "_critical_step", scene_text(p, c, 1e-7, 1));
        dt = probe.value("status", "") == "ok" ? 0.9 * probe["solver"]["critical_dt_s"].get<double>() : 1e-4;
      }
      const Json summary = runner.run(p.name + "_" + c.label, scene_text(p, c, dt, steps));
      const bool ok = summary.value("status", "") == "ok";
      Json point = {{"problem", p.name}, {"configuration", c.label}};
      if (ok) {
        const double median = summary["timing"]["step_ms"]["median"].get<double>();
        point.update({{"nodes", summary["counts"]["nodes"]}, {"dofs", summary["counts"]["dofs"]}, {"dt_s", dt},
                      {"steps", steps}, {"step_median_ms", median},
                      {"step_mean_ms", summary["timing"]["step_ms"]["mean"]},
                      {"assembly_ms", phase_ms_per_step(summary, "assembly", steps)},
                      {"factorize_ms", phase_ms_per_step(summary, "factorize", steps)},
                      {"solve_ms", phase_ms_per_step(summary, "solve", steps)}, {"setup_s", summary["timing"]["setup_s"]},
                      {"fps", 1e3 / median}, {"status", "ok"}});
        table.row({p.name, c.label, point["nodes"], point["dofs"], dt, steps, median, point["step_mean_ms"],
                   point["assembly_ms"], point["factorize_ms"], point["solve_ms"], point["setup_s"], point["fps"],
                   "ok"});
        runner.say(p.name + " " + c.label + ": " + std::to_string(median) + " ms a step (" +
                   point["nodes"].dump() + " nodes)");
      } else {
        point["status"] = summary.value("error", std::string("failed"));
        table.row({p.name, c.label, Json(), Json(), dt, steps, Json(), Json(), Json(), Json(), Json(), Json(),
                   Json(), "error"});
      }
      points.push_back(point);
    }
  }

  // 3. Write, with the paper's figures beside ours, and plot.
  Json headline = Json::array();
  for (const Json& p : points)
    if (p["status"] == "ok")
      headline.push_back({{"what", p["problem"].get<std::string>() + " " + p["configuration"].get<std::string>() +
                                       " step (" + p["nodes"].dump() + " nodes)"},
                          {"value", p["step_median_ms"]},
                          {"unit", "ms"}});
  const Json paper = {{"fem_ms_per_step", 195.0}, {"meshless_ms_per_step", 20.11}, {"block_fps", 125.0},
                      {"source", "paper section 4 and Fig. 14: SOFA on a 2.67 GHz Core i5"}};
  write_json(runner.out_dir() + "/timing.json", {{"study", "timing"},
                                                 {"quick", options.quick},
                                                 {"paper", paper},
                                                 {"headline", headline},
                                                 {"plots", {"timing.png"}},
                                                 {"points", points}});
  plot("timing", runner.out_dir());

  // 4. The claims: every configuration ran, its phases were timed and fit in its steps.
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

}  // namespace kerf
