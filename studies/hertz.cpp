// Hertz study: a rigid sphere pressed into an elastic block, every method
// against Hertz's solution (the paper's section 4 and Fig. 2, done properly).
//
//   kerf study hertz [--quick] [--out DIR]
//
// A sphere of radius R = 10 mm is pushed with the force that, on an elastic
// half-space, gives a contact radius a = R / 10 = 1 mm and an indentation
// d = a^2 / R = 0.1 mm (Hertz: F = 4/3 E* sqrt(R) d^(3/2), E* = E / (1 - nu^2)).
// The half-space is a quarter model: the block's faces x = 0 and y = 0 are
// symmetry planes, the sphere's centre lies on their common edge and carries
// a quarter of the force. Two families of discretizations:
//   graded:  nested boxes around the contact, each twice the size and spacing
//            of the one inside it, out to a block 384 a deep: the half-space
//            assumption holds there to a fraction of a percent;
//   uniform: one spacing on a block 8 a deep (the paper's setting), where the
//            block's size, not the resolution, sets the error.
// Each method (fem tet4, fem tet10, efg, nodal integration with smoothed
// gradients, and with the paper's direct ones) runs at several finest
// spacings; the indentation error against Hertz is plotted against the node
// count. Claims: every planned point runs; in full mode every method but
// direct nodal is within 2% at its finest planned graded level, and better
// than at its coarsest, and every uniform point stays more than 5% off (the
// block sets the error); in quick mode within 6% (tet4 also falls from a/2 to
// a/4). Direct nodal is reported only.
#include <cmath>

#include "studies/study_hertz_problem.h"
#include "studies/study_support.h"

namespace kerf {
namespace {

using namespace hertz;

/// One method of the study and the finest spacings (a / n) it runs at.
struct Method {
  std::string label;
  MethodChoice discretization;
  bool claimed;  // held to the bound (the paper's direct nodal gradients are reported only)
  std::vector<int> graded_full, graded_quick, uniform;
};

}  // namespace

void hertz_study(const StudyOptions& options) {
  // 1. What runs. tet4 converges as h and needs a/12 for 2%; the others reach
  // it at a/4, where tet10 and EFG already take half a minute each.
  const std::vector<Method> methods{
      {"fem_tet4", {"fem", "tet4"}, true, {2, 4, 8, 12}, {2, 4}, {2, 3, 4}},
      {"fem_tet10", {"fem", "tet10"}, true, {2, 4}, {2}, {2}},
      {"efg", {"efg"}, true, {2, 4}, {2}, {2}},
      {"nodal_smoothed", {"nodal", "tet4", "smoothed"}, true, {2, 4}, {2}, {2}},
      {"nodal", {"nodal", "tet4", "direct"}, false, {2, 4}, {2}, {2}},
  };
  auto graded = [&](const Method& m) { return options.quick ? m.graded_quick : m.graded_full; };
  auto uniform = [&](const Method& m) { return options.quick ? std::vector<int>{} : m.uniform; };
  int planned = 0;
  for (const Method& m : methods) planned += static_cast<int>(graded(m).size() + uniform(m).size());
  StudyRunner runner("hertz", options, planned);
  runner.say("Hertz indentation " + std::to_string(indentation()) + " m under " + std::to_string(force()) +
             " N (a quarter of it on the quarter model)");

  // 2. Run every point; a failed run is recorded, not fatal.
  CsvTable table(runner.out_dir() + "/hertz.csv", {"method", "family", "spacing_m", "a_over_h", "nodes", "dofs",
                                                   "indentation_m", "error_percent", "setup_s", "solve_s", "status"});
  Json points = Json::array();
  auto record = [&](const Method& d, const std::string& family, int n, double h, const Json& summary) {
    const bool ok = summary.value("status", "") == "ok";
    const double depth = ok ? summary["probes"]["indent"]["indentation"].get<double>() : NAN;
    const double error = 100.0 * (depth - indentation()) / indentation();
    Json point = {{"method", d.label}, {"family", family}, {"spacing_m", h}, {"a_over_h", n},
                  {"nodes", ok ? summary["counts"]["nodes"] : Json()}, {"dofs", ok ? summary["counts"]["dofs"] : Json()},
                  {"indentation_m", ok ? Json(depth) : Json()}, {"error_percent", ok ? Json(error) : Json()},
                  {"setup_s", ok ? summary["timing"]["setup_s"] : Json()},
                  {"solve_s", ok ? summary["timing"]["solve_s"] : Json()},
                  {"status", ok ? std::string("ok") : summary.value("error", std::string("failed"))}};
    std::vector<Json> row;
    for (const auto& [key, value] : point.items()) row.push_back(key == "status" && !ok ? Json("error") : value);
    table.row(row);
    points.push_back(point);
  };
  for (const Method& d : methods) {
    for (int n : graded(d)) {
      const std::string label = "graded_" + d.label + "_a" + std::to_string(n);
      record(d, "graded", n, contact_radius / n, runner.run(label, graded_scene(d.discretization, n)));
    }
    for (int n : uniform(d)) {
      const double h = contact_radius / n;
      const std::string label = "uniform_" + d.label + "_a" + std::to_string(n);
      record(d, "uniform", n, h, runner.run(label, scene(d.discretization, uniform_block, h, "")));
    }
  }

  // 3. The headline: each method's error at its finest graded level.
  Json finest = Json::object();
  for (const Json& p : points)
    if (p["family"] == "graded" && p["status"] == "ok") finest[p["method"].get<std::string>()] = p;
  const double bound = options.quick ? 6.0 : 2.0;
  Json headline = Json::array();
  for (const auto& [method, p] : finest.items())
    headline.push_back({{"what", method + " indentation error at a/h = " + p["a_over_h"].dump() + ", " +
                                     p["nodes"].dump() + " nodes"},
                        {"value", p["error_percent"]},
                        {"unit", "%"}});
  Json result = {{"study", "hertz"},
                 {"headline", headline},
                 {"plots", {"hertz.png"}},
                 {"quick", options.quick},
                 {"hertz", {{"contact_radius_m", contact_radius}, {"sphere_radius_m", sphere_radius},
                            {"indentation_m", indentation()}, {"force_N", force()},
                            {"young_Pa", young}, {"poisson", poisson}}},
                 {"bound_percent", bound},
                 {"finest_graded", finest},
                 {"points", points}};
  write_json(runner.out_dir() + "/hertz.json", result);
  plot("hertz", runner.out_dir());

  // 4. The claims. Every planned point must have run: a crash at the finest
  // level must not move the check to a coarser one.
  for (const Json& p : points)
    check_claim(p["status"] == "ok", p["method"].get<std::string>() + " " + p["family"].get<std::string>() +
                                         " at a/h = " + p["a_over_h"].dump() + " ran (" + p["status"].dump() + ")");
  auto graded_error = [&](const std::string& method, int n) {
    for (const Json& p : points)
      if (p["method"] == method && p["family"] == "graded" && p["a_over_h"] == n)
        return std::abs(p["error_percent"].get<double>());
    return std::nan("");
  };
  for (const Method& d : methods) {
    const std::string& m = d.label;
    const int finest_n = graded(d).back(), coarsest_n = graded(d).front();
    const double error = graded_error(m, finest_n);
    runner.say(m + ": " + std::to_string(error) + " % at a/h = " + std::to_string(finest_n) +
               (d.claimed ? "" : ", reported only"));
    if (!d.claimed) continue;
    check_claim(error < bound, m + " indentation within " + std::to_string(bound) +
                                   " % of Hertz at its finest graded level a/" + std::to_string(finest_n) +
                                   " (it is " + std::to_string(error) + " %)");
    if (finest_n != coarsest_n)
      check_claim(error < graded_error(m, coarsest_n),
                  m + " error falls from a/h = " + std::to_string(coarsest_n) + " to a/h = " + std::to_string(finest_n));
  }
  // The uniform 8 a block, not the resolution, sets the error of the paper's setting.
  for (const Json& p : points)
    if (p["family"] == "uniform")
      check_claim(std::abs(p["error_percent"].get<double>()) > 5.0,
                  p["method"].get<std::string>() + " on the uniform 8 a block at a/h = " + p["a_over_h"].dump() +
                      " stays more than 5 % off Hertz (it is " + p["error_percent"].dump() + " %)");
}

}  // namespace kerf
