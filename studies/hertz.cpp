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
// spacings a / n with n even (so each coarser lattice of the grading falls
// on the finer one: the finest box's edge 1.5 a is a multiple of a / n); the
// indentation error against Hertz is plotted against the node count.
//
// The converged answer is not Hertz's: tet10 at a / 4 and a / 6 agree to
// 0.02% and sit 1.2% below Hertz, whose idealisations (a paraboloid for the
// sphere, a half-space, small strain) are not this problem's. The reference
// is tet10 at its finest graded level (a / 6), and each method's observed
// order is fitted to its error against that reference over the levels where
// the error is larger than twice the contact's own tolerance (0.1% of the
// travel).
//
// Claims (full): every planned point runs; the reference's last two levels
// agree to 0.1%; every claimed method (all but direct nodal, reported only)
// is within 2% of Hertz and within 1% of the reference at its finest level,
// closer to Hertz than at its coarsest (smoothed nodal, which swings level by
// level, instead within 1% of the reference at every level); tet4's order is
// at least 1; every uniform point stays more than 5% off (the 8 a block sets the error); the
// reference equals the one quick mode uses. Quick: each claimed method at
// its finest quick level is within its quick bound of Hertz's formula (2%,
// tet4 5% at a / 4) and, where it has two levels and is monotone, closer to
// Hertz at the finer; each method's error against the reference at a / 2 and
// a / 4 is what the full study measured (to 0.05 points), and so is tet4's
// order between the two.
#include <cmath>
#include <cstdio>

#include "core/check.h"
#include "studies/study_hertz_problem.h"
#include "studies/study_support.h"

namespace kerf {
namespace {

using namespace hertz;

/// One method of the study and the finest spacings (a / n, n even) it runs at.
struct Way {
  std::string label;
  MethodChoice discretization;
  bool claimed;  // held to the bounds (the paper's direct nodal gradients are reported only)
  bool monotone;  // closer to Hertz at its finest level than at its coarsest (smoothed nodal swings: not)
  std::vector<int> graded_full, graded_quick, uniform;
  double quick_hertz_bound;  // %: off Hertz at its finest quick level, at most (claimed methods)
};

const std::vector<Way>& study_methods() {
  // tet4 converges as h and needs a/12 for 2%; the others reach it at a/4.
  static const std::vector<Way> methods{
      // The quick bounds sit above the full study's errors at those levels
      // (tet4 4.47% at a/4, tet10 1.62% at a/2, efg 1.23% and smoothed 0.52% at a/4).
      {"fem_tet4", {Method::fem}, true, true, {2, 4, 6, 8, 12}, {2, 4}, {2, 3, 4}, 5.0},
      {"fem_tet10", {Method::fem, ElementType::tet10}, true, true, {2, 4, 6}, {2}, {2}, 2.0},
      {"efg", {Method::efg}, true, true, {2, 4, 6, 8}, {2, 4}, {2}, 2.0},
      {"nodal_smoothed", {Method::nodal, ElementType::tet4, NodalGradient::smoothed}, true, false, {2, 4, 6, 8},
       {2, 4}, {2}, 2.0},
      {"nodal", {Method::nodal}, false, false, {2, 4, 6, 8}, {2}, {2}, 0.0},
  };
  return methods;
}

// The reference (tet10 at a/6, from the full study) and what the full study
// measured at the quick levels: the quick mode is held to them. Made by
// `kerf study hertz` (full, 2 threads) at commit c4c83e8 (2026-11-24),
// results/hertz/hertz.csv; ctest checks the quick mode at 1 and 2 threads.
constexpr double reference_indentation = 9.8814569445e-05;  // m
constexpr const char* reference_method = "fem_tet10";
struct QuickFigure {
  const char* method;
  int n;
  double error_vs_reference;  // %
};
constexpr QuickFigure measured_at_quick_levels[] = {
    {"fem_tet4", 2, -9.5074}, {"fem_tet4", 4, -3.3262},       {"fem_tet10", 2, -0.4443}, {"efg", 2, -2.1959},
    {"efg", 4, -0.0464},      {"nodal_smoothed", 2, 0.0360}, {"nodal_smoothed", 4, 0.6739}, {"nodal", 2, -3.1216},
};
constexpr double quick_margin = 0.05;      // percentage points
constexpr double hertz_bound = 2.0;        // %: claimed methods at their finest level
constexpr double reference_bound = 1.0;    // %: the same against the reference
constexpr double contact_tolerance = 0.1;  // % of the travel a point may penetrate (contact_term.cpp)
constexpr double fit_floor = 2.0 * contact_tolerance;

const Way& reference_of_study() {
  for (const Way& m : study_methods())
    if (m.label == reference_method) return m;
  throw Error("internal: the Hertz study has no method " + std::string(reference_method));
}

const Json* find_point(const Json& points, const std::string& method, const std::string& family, int n) {
  for (const Json& p : points)
    if (p["method"] == method && p["family"] == family && p["a_over_h"] == n && p["status"] == "ok") return &p;
  return nullptr;
}

/// Each method's observed order against the reference over the graded levels
/// whose error is above the contact's tolerance (null below two such levels).
Json observed_rates(const Json& points) {
  Json rates = Json::object();
  for (const Way& m : study_methods()) {
    std::vector<double> h, error;
    Json levels = Json::array();
    for (const Json& p : points)
      if (p["method"] == m.label && p["family"] == "graded" && p["status"] == "ok" &&
          p["error_vs_reference_percent"].is_number() &&
          std::abs(p["error_vs_reference_percent"].get<double>()) > fit_floor) {
        h.push_back(p["spacing_m"]);
        error.push_back(p["error_vs_reference_percent"]);
        levels.push_back(p["a_over_h"]);
      }
    rates[m.label] = {{"order", h.size() >= 2 ? Json(observed_order(h, error)) : Json()}, {"levels", levels}};
  }
  return rates;
}

/// The claims of the full study (see the header).
void check_full_claims(const Json& points, const Json& rates, double reference) {
  const std::vector<int>& levels = reference_of_study().graded_full;
  const int last = levels.back(), before = levels[levels.size() - 2];
  const double agreement =
      percent_off((*find_point(points, reference_method, "graded", before))["indentation_m"], reference);
  check_claim(std::abs(agreement) < 0.1, "the reference has converged: tet10 at a/" + std::to_string(before) +
                                             " is within 0.1 % of a/" + std::to_string(last) + " (" +
                                             std::to_string(agreement) + " %)");
  check_claim(std::abs(percent_off(reference, reference_indentation)) < 1e-6,
              "the reference equals the one quick mode uses (" + std::to_string(reference) +
                  " m; update reference_indentation)");
  for (const Way& d : study_methods()) {
    if (!d.claimed) continue;
    const Json& finest = *find_point(points, d.label, "graded", d.graded_full.back());
    const Json& coarsest = *find_point(points, d.label, "graded", d.graded_full.front());
    const double hertz_error = std::abs(finest["error_percent"].get<double>());
    const double reference_error = std::abs(finest["error_vs_reference_percent"].get<double>());
    const std::string at = d.label + " at its finest graded level a/" + finest["a_over_h"].dump();
    check_claim(hertz_error < hertz_bound, at + " is within " + std::to_string(hertz_bound) + " % of Hertz (" +
                                               std::to_string(hertz_error) + " %)");
    check_claim(reference_error < reference_bound, at + " is within " + std::to_string(reference_bound) +
                                                       " % of the reference (" + std::to_string(reference_error) +
                                                       " %)");
    if (d.monotone) {
      check_claim(hertz_error < std::abs(coarsest["error_percent"].get<double>()),
                  d.label + " is closer to Hertz at a/" + finest["a_over_h"].dump() + " than at a/" +
                      coarsest["a_over_h"].dump());
      continue;
    }
    // Smoothed nodal swings about the reference level by level (measured
    // +0.04 / +0.67 / -0.88 / -0.77 % at a/2 ... a/8): held within 1 % at each.
    for (int n : d.graded_full) {
      const double e = (*find_point(points, d.label, "graded", n))["error_vs_reference_percent"];
      check_claim(std::abs(e) < reference_bound, d.label + " at a/" + std::to_string(n) + " is within " +
                                                     std::to_string(reference_bound) + " % of the reference (" +
                                                     std::to_string(e) + " %)");
    }
  }
  const Json& tet4 = rates["fem_tet4"]["order"];
  check_claim(tet4.is_number() && tet4.get<double>() >= 1.0, "tet4's observed order is at least 1 (" + tet4.dump() + ")");
  for (const Json& p : points)
    if (p["family"] == "uniform")
      check_claim(std::abs(p["error_percent"].get<double>()) > 5.0,
                  p["method"].get<std::string>() + " on the uniform 8 a block at a/h = " + p["a_over_h"].dump() +
                      " stays more than 5 % off Hertz (it is " + p["error_percent"].dump() + " %)");
}

/// Quick mode, against Hertz's formula: each claimed method at its finest
/// quick level within its bound, and closer than at its coarsest where monotone.
void check_quick_hertz_claims(const Json& points) {
  for (const Way& m : study_methods()) {
    if (!m.claimed) continue;
    const Json* finest = find_point(points, m.label, "graded", m.graded_quick.back());
    const Json* coarsest = find_point(points, m.label, "graded", m.graded_quick.front());
    if (!finest || !coarsest) continue;  // a failed point is a claim of its own
    const double error = std::abs((*finest)["error_percent"].get<double>());
    const std::string at = m.label + " at a/" + std::to_string(m.graded_quick.back());
    check_claim(error < m.quick_hertz_bound, at + " is within " + std::to_string(m.quick_hertz_bound) +
                                                 " % of Hertz (" + std::to_string(error) + " %)");
    if (m.monotone && finest != coarsest)
      check_claim(error < std::abs((*coarsest)["error_percent"].get<double>()),
                  m.label + " is closer to Hertz at a/" + std::to_string(m.graded_quick.back()) + " than at a/" +
                      std::to_string(m.graded_quick.front()));
  }
}

/// Quick mode: the errors and orders at its levels are the full study's.
void check_quick_claims(const Json& points) {
  check_quick_hertz_claims(points);
  auto error_of = [&](const std::string& method, int n) {
    const Json* p = find_point(points, method, "graded", n);
    return p ? (*p)["error_vs_reference_percent"].get<double>() : NAN;
  };
  auto measured = [](const std::string& method, int n) {
    for (const QuickFigure& q : measured_at_quick_levels)
      if (q.method == method && q.n == n) return q.error_vs_reference;
    return static_cast<double>(NAN);
  };
  for (const QuickFigure& q : measured_at_quick_levels) {
    const double error = error_of(q.method, q.n);
    check_claim(std::abs(error - q.error_vs_reference) < quick_margin,
                std::string(q.method) + " at a/" + std::to_string(q.n) +
                    " is off the reference by what the full study measured (" + std::to_string(error) +
                    " % against " + std::to_string(q.error_vs_reference) + " %)");
  }
  // tet4's order: the meshless errors at a/4 are near the contact's tolerance,
  // where an order is noise (their errors are held above).
  const double order = std::log(error_of("fem_tet4", 2) / error_of("fem_tet4", 4)) / std::log(2.0);
  const double full = std::log(measured("fem_tet4", 2) / measured("fem_tet4", 4)) / std::log(2.0);
  check_claim(std::abs(order - full) < 0.05,
              "tet4's order from a/2 to a/4 is the full study's (" + std::to_string(order) + " against " +
                  std::to_string(full) + ")");
}

/// ", observed order 1.52" (two decimals), or "" where no order was fitted
/// (a single level, or errors within the contact's tolerance).
std::string order_in_words(const Json& order) {
  if (!order.is_number()) return "";
  char text[32];
  std::snprintf(text, sizeof text, ", observed order %.2f", order.get<double>());
  return text;
}

/// hertz.csv, hertz.json (the headline: each method's finest graded level) and the plot.
void write_results(const StudyRunner& runner, const StudyOptions& options, const Json& points, const Json& rates,
                   double reference) {
  const std::vector<std::string> columns{"method",        "family", "spacing_m",     "a_over_h",
                                         "nodes",         "dofs",   "indentation_m", "error_percent",
                                         "error_vs_reference_percent", "setup_s", "solve_s", "run_s", "status"};
  CsvTable table(runner.out_dir() + "/hertz.csv", columns);
  for (const Json& p : points) {
    std::vector<Json> row;
    for (const std::string& c : columns) row.push_back(c == "status" && p[c] != "ok" ? Json("error") : p[c]);
    table.row(row);
  }
  Json finest = Json::object();
  for (const Json& p : points)
    if (p["family"] == "graded" && p["status"] == "ok") finest[p["method"].get<std::string>()] = p;
  StudyResult result("hertz", options.quick, {"hertz.png"});
  for (const auto& [method, p] : finest.items())
    result.headline(method + " indentation error at a/h = " + p["a_over_h"].dump() + ", " + p["nodes"].dump() +
                        " nodes" + order_in_words(rates[method]["order"]),
                    p["error_percent"], "%");
  result["hertz"] = {{"contact_radius_m", contact_radius}, {"sphere_radius_m", sphere_radius},
                     {"indentation_m", indentation()}, {"force_N", force()}, {"young_Pa", young}, {"poisson", poisson}};
  result["reference"] = {{"method", reference_method}, {"indentation_m", reference},
                         {"off_hertz_percent", percent_off(reference, indentation())},
                         {"from_quick_constant", options.quick}};
  result["rates_against_reference"] = rates;
  result["fit_floor_percent"] = fit_floor;
  result["bound_percent"] = hertz_bound;
  result["finest_graded"] = finest;
  result["points"] = points;
  result.write(runner.out_dir());
  plot("hertz", runner.out_dir());
}

}  // namespace

void hertz_study(const StudyOptions& options) {
  // 1. What runs.
  const std::vector<Way>& methods = study_methods();
  auto graded = [&](const Way& m) { return options.quick ? m.graded_quick : m.graded_full; };
  auto uniform = [&](const Way& m) { return options.quick ? std::vector<int>{} : m.uniform; };
  int planned = 0;
  for (const Way& m : methods) planned += static_cast<int>(graded(m).size() + uniform(m).size());
  StudyRunner runner("hertz", options, planned);
  runner.say("Hertz indentation " + std::to_string(indentation()) + " m under " + std::to_string(force()) +
             " N (a quarter of it on the quarter model)");

  // 2. Run every point; a failed run is recorded, not fatal.
  Json points = Json::array();
  auto record = [&](const Way& d, const std::string& family, int n, double h, const RunRecord& run) {
    const bool ok = run.ok();
    const double depth = ok ? run.probe("indent") : NAN;
    points.push_back({{"method", d.label}, {"family", family}, {"spacing_m", h}, {"a_over_h", n},
                      {"nodes", ok ? Json(run.report.counts.nodes) : Json()},
                      {"dofs", ok ? Json(run.report.counts.dofs) : Json()},
                      {"indentation_m", ok ? Json(depth) : Json()},
                      {"error_percent", ok ? Json(percent_off(depth, indentation())) : Json()},
                      {"error_vs_reference_percent", Json()},
                      {"setup_s", ok ? Json(run.report.setup_seconds) : Json()},
                      {"solve_s", ok ? Json(run.report.solve_seconds) : Json()},
                      {"run_s", ok ? Json(whole_run_seconds(run)) : Json()},
                      {"status", ok ? std::string("ok") : run.error}});
  };
  for (const Way& d : methods) {
    for (int n : graded(d)) {
      const std::string label = "graded_" + d.label + "_a" + std::to_string(n);
      record(d, "graded", n, contact_radius / n, runner.run(label, graded_scene(d.discretization, n)));
    }
    for (int n : uniform(d)) {
      const double h = contact_radius / n;
      const std::string label = "uniform_" + d.label + "_a" + std::to_string(n);
      record(d, "uniform", n, h, runner.run(label, scene(d.discretization, uniform_block, h)));
    }
  }

  // 3. The reference: tet10 at its finest level (full), the full study's value (quick).
  // Written before any claim: a failed point must not lose the others.
  const Json* finest_tet10 = find_point(points, reference_method, "graded", reference_of_study().graded_full.back());
  const double reference = options.quick ? reference_indentation
                           : finest_tet10 ? (*finest_tet10)["indentation_m"].get<double>()
                                          : NAN;
  for (Json& p : points)
    if (p["family"] == "graded" && p["status"] == "ok")
      p["error_vs_reference_percent"] = percent_off(p["indentation_m"], reference);
  const Json rates = observed_rates(points);
  write_results(runner, options, points, rates, reference);

  // 4. The claims. Every planned point must have run: a crash at the finest
  // level must not move the check to a coarser one.
  for (const Json& p : points)
    check_claim(p["status"] == "ok", p["method"].get<std::string>() + " " + p["family"].get<std::string>() +
                                         " at a/h = " + p["a_over_h"].dump() + " ran (" + p["status"].dump() + ")");
  for (const Way& d : methods)
    runner.say(d.label + ": " + std::to_string((*find_point(points, d.label, "graded", graded(d).back()))
                                                   ["error_percent"].get<double>()) +
               " % off Hertz at a/" + std::to_string(graded(d).back()) + order_in_words(rates[d.label]["order"]) +
               (d.claimed ? "" : ", reported only"));
  if (options.quick)
    check_quick_claims(points);
  else
    check_full_claims(points, rates, reference);
}

}  // namespace kerf
