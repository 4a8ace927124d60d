// Pareto study: wall time against error for every method and resolution, on
// two problems, the plot a user reads to choose a method.
//
//   kerf study pareto [--quick] [--out DIR]
//
// Hertz: the hertz study's graded quarter block (studies/hertz.cpp), the
//        indentation against Hertz's solution.
// Crack: scenes/crack_plate_2d.yaml, a 2 cm crack in a plate under remote
//        tension (plane strain, static), the opening vector at the crack's
//        centre against fem remesh tri6 of 0.1 mm around the crack.
// Wall time: the run's setup plus solve (meshing, shape functions, assembly,
// factorization, contact rounds), one run at a time on this machine. Each
// problem's Pareto front (the points no other point beats in both time and
// error) is written to pareto.json. `fem: remove` is left out of the crack:
// its crack is a gap a cell wide, whose faces are not where the others' are
// (results/crack_opening.md compares it 1.5 mm off the faces).
// Claims: every point ran; every method at its finest level is within 6% of
// Hertz and 5% of the crack reference, and its Hertz error falls from its
// coarsest to its finest level (direct nodal on Hertz: reported only); in full
// mode, as results/cost.md says, smoothed nodal integration beats tet4's
// finest on Hertz and EFG's finest beats every FEM point on the crack.
#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

#include "core/check.h"
#include "problem/scene_reader.h"
#include "studies/study_hertz_problem.h"
#include "studies/study_support.h"

namespace kerf {
namespace {

struct Point {
  Point(std::string problem, std::string method, double resolution)
      : problem(std::move(problem)), method(std::move(method)), resolution(resolution) {}
  std::string problem, method;
  double resolution;  // a / h (Hertz) or h in m (crack)
  RunRecord run;
  double error_percent = NAN;  // |error|
  double wall_s = NAN;
  bool ok() const { return std::isfinite(error_percent); }
};

double wall_time(const RunRecord& run) { return run.report.setup_seconds + run.report.solve_seconds; }

/// The opening u(upper face) - u(lower face) at the crack's centre (m).
std::array<double, 2> opening(const RunRecord& run) {
  return {run.probe("upper_face", 0) - run.probe("lower_face", 0), run.probe("upper_face", 1) - run.probe("lower_face", 1)};
}

/// The crack plate (scenes/crack_plate_2d.yaml) by `method` and `element` at resolution `h` (m), no ParaView files.
Scene crack_plate(Method method, ElementType element, NodalGradient gradient, double h) {
  Scene scene = read_scene(study_data_path("scenes/crack_plate_2d.yaml"));
  scene.discretization.method = method;
  scene.discretization.fem.element = element;
  scene.discretization.meshless.gradient = gradient;
  (method == Method::fem ? scene.discretization.fem.size : scene.discretization.meshless.spacing) = h;
  scene.output.vtk_every = 0;
  return scene;
}

/// Indices of the points no other point beats in both wall time and error, fastest first.
std::vector<std::size_t> pareto_front(const std::vector<Point>& points, const std::string& problem) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (points[i].problem == problem && points[i].ok()) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return points[a].wall_s < points[b].wall_s; });
  std::vector<std::size_t> front;
  double best = INFINITY;
  for (std::size_t i : order)
    if (points[i].error_percent < best) {
      best = points[i].error_percent;
      front.push_back(i);
    }
  return front;
}

/// What runs of Hertz: the graded block at finest spacings a / n.
struct HertzMethod {
  std::string label;
  hertz::MethodChoice discretization;
  std::vector<int> levels;
};

std::vector<HertzMethod> hertz_methods(bool quick) {
  const hertz::MethodChoice tet4{Method::fem}, tet10{Method::fem, ElementType::tet10}, efg{Method::efg},
      smoothed{Method::nodal, ElementType::tet4, NodalGradient::smoothed}, nodal{Method::nodal};
  if (quick) return {{"fem_tet4", tet4, {2, 4}}, {"nodal_smoothed", smoothed, {2}}};
  return {{"fem_tet4", tet4, {2, 4, 8}},
          {"fem_tet10", tet10, {2, 4}},
          {"efg", efg, {2, 4}},
          {"nodal_smoothed", smoothed, {2, 4}},
          {"nodal", nodal, {2, 4}}};
}

/// What runs of the crack: node spacings or element sizes h.
struct CrackMethod {
  std::string label;
  Method method;
  ElementType element;
  NodalGradient gradient;
  std::vector<std::string> spacings;  // as the labels spell them
};

std::vector<CrackMethod> crack_methods(bool quick) {
  using Spacings = std::vector<std::string>;
  const Spacings meshless = quick ? Spacings{"0.001"} : Spacings{"0.001", "0.000745", "0.0005", "0.0004"};
  const Spacings tri3 = quick ? Spacings{"0.001"} : Spacings{"0.001", "0.0005", "0.00025"};  // 2 mm: no node by the support
  const Spacings tri6 = quick ? Spacings{"0.001"} : Spacings{"0.002", "0.001", "0.0005"};
  return {
      {"nodal", Method::nodal, ElementType::tri3, NodalGradient::direct, meshless},
      {"nodal_smoothed", Method::nodal, ElementType::tri3, NodalGradient::smoothed, meshless},
      {"efg", Method::efg, ElementType::tri3, NodalGradient::direct, meshless},
      {"fem_tri3", Method::fem, ElementType::tri3, NodalGradient::direct, tri3},
      {"fem_tri6", Method::fem, ElementType::tri6, NodalGradient::direct, tri6},
  };
}

void run_hertz(StudyRunner& runner, bool quick, std::vector<Point>& points) {
  for (const HertzMethod& m : hertz_methods(quick))
    for (int n : m.levels) {
      Point p{"hertz", m.label, static_cast<double>(n)};
      p.run = runner.run("hertz_" + m.label + "_a" + std::to_string(n), hertz::graded_scene(m.discretization, n));
      if (p.run.ok()) {
        const double depth = p.run.probe("indent");
        p.error_percent = 100.0 * std::abs(depth - hertz::indentation()) / hertz::indentation();
        p.wall_s = wall_time(p.run);
      }
      points.push_back(p);
    }
}

/// The crack's runs against its reference; answers the reference's opening.
std::array<double, 2> run_crack(StudyRunner& runner, bool quick, std::vector<Point>& points) {
  // The reference: tri6, 0.5 mm, refined to 0.1 mm about the crack.
  Scene fine = crack_plate(Method::fem, ElementType::tri6, NodalGradient::direct, 0.0005);
  fine.discretization.refine = {{Box{Vec3(-0.012, -0.003, 0), Vec3(0.012, 0.003, 0)}, 0.0001}};
  const RunRecord reference = runner.run("crack_reference", fine);
  KERF_CHECK(reference.ok(), "the crack reference (fem remesh tri6) failed: ", reference.error);
  const std::array<double, 2> exact = opening(reference);
  for (const CrackMethod& m : crack_methods(quick))
    for (const std::string& h : m.spacings) {
      Point p{"crack", m.label, std::stod(h)};
      p.run = runner.run("crack_" + m.label + "_h" + h, crack_plate(m.method, m.element, m.gradient, std::stod(h)));
      if (p.run.ok()) {
        const std::array<double, 2> delta = opening(p.run);
        p.error_percent =
            100.0 * std::hypot(delta[0] - exact[0], delta[1] - exact[1]) / std::hypot(exact[0], exact[1]);
        p.wall_s = wall_time(p.run);
      }
      points.push_back(p);
    }
  return exact;
}

/// pareto.csv and pareto.json: every point, and each problem's front with its headline.
void write_results(const StudyRunner& runner, bool quick, const std::vector<Point>& points,
                   const std::array<double, 2>& exact) {
  CsvTable table(runner.out_dir() + "/pareto.csv",
                 {"problem", "method", "resolution", "nodes", "dofs", "wall_s", "error_percent", "status"});
  Json all = Json::array();
  for (const Point& p : points) {
    const bool ok = p.ok();
    Json row = {{"problem", p.problem}, {"method", p.method}, {"resolution", p.resolution},
                {"nodes", ok ? Json(p.run.report.counts.nodes) : Json()},
                {"dofs", ok ? Json(p.run.report.counts.dofs) : Json()},
                {"wall_s", ok ? Json(p.wall_s) : Json()}, {"error_percent", ok ? Json(p.error_percent) : Json()},
                {"status", ok ? std::string("ok") : p.run.error}};
    table.row({row["problem"], row["method"], row["resolution"], row["nodes"], row["dofs"], row["wall_s"],
               row["error_percent"], ok ? Json("ok") : Json("error")});
    all.push_back(row);
  }
  StudyResult result("pareto", quick, {"pareto.png"});
  Json fronts = Json::object();
  for (const std::string problem : {"hertz", "crack"}) {
    Json front = Json::array();
    for (std::size_t i : pareto_front(points, problem)) {
      front.push_back(all[i]);
      std::ostringstream what;
      what << problem << " front: " << points[i].method << " at "
           << (problem == "hertz" ? "a/h = " : "h = ") << points[i].resolution << (problem == "hertz" ? "" : " m")
           << ", " << std::setprecision(3) << points[i].wall_s << " s";
      result.headline(what.str(), points[i].error_percent, "%");
    }
    fronts[problem] = front;
  }
  result["crack_reference_opening_m"] = exact;
  result["fronts"] = fronts;
  result["points"] = all;
  result.write(runner.out_dir());
}

void check_pareto_claims(const std::vector<Point>& points, bool quick) {
  for (const Point& p : points)
    check_claim(p.ok(), p.problem + " " + p.method + " at " + std::to_string(p.resolution) + " ran");
  std::map<std::string, std::map<std::string, std::vector<const Point*>>> series;  // problem, method: coarsest first
  for (const Point& p : points) series[p.problem][p.method].push_back(&p);
  for (const auto& [problem, methods] : series) {
    const double bound = problem == "hertz" ? 6.0 : 5.0;
    for (const auto& [method, levels] : methods) {
      // The paper's direct nodal gradients break down on the graded lattice at
      // a/4 (results/contact.md): reported, not claimed.
      if (problem == "hertz" && method == "nodal") continue;
      const double finest = levels.back()->error_percent;
      check_claim(finest < bound, problem + ": " + method + " at its finest level is within " +
                                      std::to_string(bound) + " % (it is " + std::to_string(finest) + " %)");
      if (problem == "hertz" && levels.size() > 1)
        check_claim(finest < levels.front()->error_percent,
                    "hertz: " + method + "'s error falls from its coarsest to its finest level");
    }
  }
  if (quick) return;
  // What results/cost.md says of the fronts in words.
  const double smoothed = series["hertz"]["nodal_smoothed"].back()->error_percent;
  const double tet4 = series["hertz"]["fem_tet4"].back()->error_percent;
  check_claim(smoothed < tet4, "hertz: smoothed nodal integration at a/4 is more accurate than tet4 at its finest (" +
                                   std::to_string(smoothed) + " against " + std::to_string(tet4) + " %)");
  const double efg = series["crack"]["efg"].back()->error_percent;
  for (const char* fem : {"fem_tri3", "fem_tri6"})
    for (const Point* p : series["crack"][fem])
      check_claim(efg < p->error_percent, std::string("crack: efg at its finest spacing is more accurate than ") + fem +
                                              " at " + std::to_string(p->resolution) + " m");
}

}  // namespace

void pareto_study(const StudyOptions& options) {
  // 1. What runs: Hertz at finest spacings a / n; the crack at node spacings or element sizes h.
  int planned = 1;
  for (const HertzMethod& m : hertz_methods(options.quick)) planned += static_cast<int>(m.levels.size());
  for (const CrackMethod& m : crack_methods(options.quick)) planned += static_cast<int>(m.spacings.size());
  StudyRunner runner("pareto", options, planned);

  // 2. The runs.
  std::vector<Point> points;
  run_hertz(runner, options.quick, points);
  const std::array<double, 2> exact = run_crack(runner, options.quick, points);

  // 3. Tables, fronts, plot; 4. the claims.
  write_results(runner, options.quick, points, exact);
  plot("pareto", runner.out_dir());
  check_pareto_claims(points, options.quick);
}

}  // namespace kerf
