// Haptic-loop study: can a method keep up with a hand on the blade at 1 kHz?
//
//   kerf study haptic [--quick] [--out DIR]
//
// A 10 cm block of soft tissue (E = 3 kPa, nu = 0.3, mass damping 10/s)
// clamped at the bottom, a rigid sphere (1 cm) held 4 mm into its top (no
// gravity: the block would sag 3 cm away from it), and a live cut (`strip: []`) fed by a session one blade
// position a step, as a haptic device gives them: a vertical blade edge from
// z = 3 cm to above the top at y = 5.03 cm, advancing along x by 0.2 mm a
// step of 1 ms (20 cm/s). Each iteration of the loop is what a haptic
// thread does: read the tool (the next blade position), cut
// (Session::extend_cut), step (Session::step), write the force
// (Session::contact_force). Methods: nodal (Enrichment Grid), EFG, and FEM
// tet4 with split elements, each at about 6 000 nodes (quick: about 1 000),
// central differences at 1 ms (EFG: two steps of 0.5 ms, below its critical
// step), with the OpenMP threads the process has. FEM
// runs without the sphere: contact with a growing FEM cut is not built (the
// scene is refused), so its loop writes no force.
//
// The floor beside it, in the same run: the same loop on the same scene
// with no blade fed (read, step, write; the live cut stays empty), so the
// difference is what cutting costs. Per iteration: median, 99th percentile
// and the largest, and from the cut run's summary the medians of the
// body's update and of the stepper's refresh (the critical step estimated
// again, Lanczos) a growth. Speed is measured here, never asserted; the
// claims checked are that the cut grew at every step and that the sphere
// pressed on the body.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <omp.h>

#include "app/session.h"
#include "core/timer.h"
#include "studies/study_scenes.h"
#include "studies/study_support.h"

namespace kerf {
namespace {

constexpr double blade_y = 0.0503;       // between node planes
constexpr double blade_start_x = 0.005;  // m
constexpr double blade_advance = 2e-4;   // m a step

struct HapticMethod {
  std::string label;
  Method method;
  int iterations;
  int steps_per_iteration = 1;  // of dt = 1 ms / this: an iteration is 1 ms of the body's time
};

Scene haptic_block(const HapticMethod& m, double spacing) {
  using namespace study_scene;
  Scene scene = box_body("haptic_" + m.label, Vec3(0, 0, 0), Vec3(0.1, 0.1, 0.1));
  scene.material = material(MaterialModel::linear, 3000.0, 0.3, 1000.0, 10.0);
  scene.discretization.method = m.method;
  scene.discretization.meshless.spacing = spacing;
  scene.discretization.meshless.support = 2.3;
  scene.discretization.fem.element = ElementType::tet4;
  scene.discretization.fem.size = spacing;
  scene.boundary = {held(2, 0.0)};
  ContactSphere sphere;
  sphere.center = Vec3(0.05, 0.075, 0.11);
  sphere.radius = 0.01;
  sphere.displacement = Vec3(0, 0, -0.004);
  if (m.method != Method::fem) scene.contact = {sphere};  // fem: contact with a growing cut is not built
  Cut blade;
  blade.is_strip = true;
  blade.live = true;
  blade.enrichment = Enrichment::grid;
  blade.grid_spacing = spacing / 10.0;
  blade.fem = FemCut::split;
  scene.cuts = {blade};
  scene.solve.analysis = Analysis::dynamic;
  scene.solve.integrator = Integrator::central_difference;
  scene.solve.dt = 0.001 / m.steps_per_iteration;
  scene.solve.duration = 0.001 * (m.iterations + 1);
  return scene;
}

/// The blade's two ends at step i (the tracker's reading).
std::array<Vec3, 2> blade_at(int i) {
  const double x = study_scene::as_written(blade_start_x + blade_advance * i);
  return {Vec3(x, blade_y, 0.11), Vec3(x, blade_y, 0.03)};
}

struct LoopFigures {
  std::vector<double> iteration_ms;
  Vec3 last_force = Vec3::Zero();
  RunOutcome outcome;
};

/// m.iterations turns of the haptic loop on `scene` in a session writing
/// into `dir`: with the blade fed every iteration, or (`cut` false) without.
LoopFigures haptic_loop(const Scene& scene, const std::string& dir, const HapticMethod& m, bool cut) {
  RunOptions options;
  options.out_dir = dir;
  options.quiet = true;
  Session session(scene, options);
  const bool pressed = !scene.contact.empty();
  if (cut) session.extend_cut(0, blade_at(0));  // the blade enters: no piece yet
  LoopFigures figures;
  for (int i = 1; i <= m.iterations; ++i) {
    const double start = now_seconds();
    if (cut) {
      const std::array<Vec3, 2> blade = blade_at(i);  // read the tool
      session.extend_cut(0, blade);                   // cut
    }
    for (int k = 0; k < m.steps_per_iteration; ++k) session.step();  // step
    if (pressed) figures.last_force = session.contact_force(0);  // write the force
    figures.iteration_ms.push_back(1e3 * (now_seconds() - start));
  }
  figures.outcome = session.finish();
  return figures;
}

double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  const std::size_t at = std::min(values.size() - 1, static_cast<std::size_t>(std::ceil(p * values.size())) - 1);
  return values[at];
}

Json loop_json(const LoopFigures& loop) {
  const RunReport& report = loop.outcome.report;
  const std::vector<double>& t = loop.iteration_ms;
  auto median_ms = [](std::vector<double> s) { return s.empty() ? 0.0 : 1e3 * percentile(std::move(s), 0.5); };
  return {{"iterations", t.size()},
          {"median_ms", percentile(t, 0.5)},
          {"p99_ms", percentile(t, 0.99)},
          {"max_ms", *std::max_element(t.begin(), t.end())},
          {"step_median_ms", median_ms(report.step_seconds)},
          {"cut_update_median_ms", median_ms(report.cut_update_seconds)},
          {"cut_refresh_median_ms", median_ms(report.cut_refresh_seconds)},
          {"growths", report.cut_update_seconds.size()},
          {"substeps_max", report.solver.substeps_max},
          {"force_z_n", loop.last_force.z()},
          {"nodes", report.counts.nodes}};
}

}  // namespace

void haptic_study(const StudyOptions& options) {
  // 1. Methods and the block's resolution.
  const double spacing = options.quick ? 0.0125 : 0.00588;
  const int scale = options.quick ? 10 : 1;
  const std::vector<HapticMethod> methods{
      {"nodal", Method::nodal, 300 / scale},
      {"efg", Method::efg, 100 / scale, 2},  // its critical step at 6k nodes: 0.68 ms
      {"fem_split", Method::fem, 100 / scale}};
  StudyRunner runner("haptic", options, 0);
  CsvTable table(runner.out_dir() + "/haptic.csv",
                 {"method", "loop", "nodes", "iterations", "median_ms", "p99_ms", "max_ms", "step_median_ms",
                  "cut_update_median_ms", "cut_refresh_median_ms", "growths", "substeps_max", "force_z_n"});
  CsvTable trace(runner.out_dir() + "/iterations.csv", {"method", "loop", "iteration", "ms"});

  // 2. Each method: the floor loop, then the cutting loop.
  Json points = Json::array();
  for (const HapticMethod& m : methods) {
    const Scene scene = runner.write_scene(m.label, haptic_block(m, spacing));
    for (const bool cut : {false, true}) {
      const std::string loop_name = cut ? "cut" : "floor";
      const LoopFigures loop =
          haptic_loop(scene, runner.out_dir() + "/runs/" + m.label + "_" + loop_name, m, cut);
      Json point = {{"method", m.label}, {"loop", loop_name}};
      point.update(loop_json(loop));
      table.row({m.label, loop_name, point["nodes"], point["iterations"], point["median_ms"], point["p99_ms"],
                 point["max_ms"], point["step_median_ms"], point["cut_update_median_ms"],
                 point["cut_refresh_median_ms"], point["growths"], point["substeps_max"], point["force_z_n"]});
      for (std::size_t i = 0; i < loop.iteration_ms.size(); ++i)
        trace.row({m.label, loop_name, static_cast<int>(i + 1), loop.iteration_ms[i]});
      runner.say(m.label + " " + loop_name + ": median " + point["median_ms"].dump() + " ms, p99 " +
                 point["p99_ms"].dump() + " ms an iteration");
      points.push_back(point);
    }
  }

  // 3. Written and plotted; 4. the claims.
  StudyResult result("haptic", options.quick, {"haptic.png"});
  for (const Json& p : points)
    if (p["loop"] == "cut")
      result.headline(p["method"].get<std::string>() + " haptic iteration, median (cut every step)", p["median_ms"],
                      "ms");
  result["threads"] = omp_get_max_threads();
  // How idle OpenMP threads wait (kerf's policy: passive; a haptic host that owns its cores may set active).
  const char* wait = std::getenv("OMP_WAIT_POLICY");
  result["omp_wait_policy"] = wait ? wait : "libgomp's default";
  result["points"] = points;
  result.write(runner.out_dir());
  plot("haptic", runner.out_dir());
  for (const Json& p : points) {
    const std::string name = p["method"].get<std::string>() + " " + p["loop"].get<std::string>();
    if (p["loop"] == "cut")
      check_claim(p["growths"] == p["iterations"], name + ": the cut grew at every step (" + p["growths"].dump() +
                                                       " growths in " + p["iterations"].dump() + " steps)");
    if (p["method"] != "fem_split")
      check_claim(p["force_z_n"].get<double>() < 0.0,
                name + ": the sphere presses on the body (force z " + p["force_z_n"].dump() + " N)");
  }
}

}  // namespace kerf
