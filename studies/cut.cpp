// Cut study: the paper's demonstration (Figs. 14-16). A soft block clamped
// at one end sags under gravity while a blade cuts into it from the top, and
// the four ways of following the cut are compared on the same problem:
// meshless nodal integration with the Enrichment Grid, FEM that meshes the
// cut in again (remesh), FEM that deletes the cells it crosses (remove) and
// FEM that splits them in two, one copy per side (split).
//
//   kerf study cut [--quick] [--out DIR]
//
// The block: 6 x 3 x 2 cm, E = 30 kPa, nu = 0.35, corotational, 1000 kg/m^3,
// mass damping 10/s, clamped at x = 0. The blade: a vertical edge from above
// the top face down to 8 mm above the bottom, at x = 2 cm, crossing the width
// (y) in 2 mm moves from t = 0.1 s, each move a new pair of strip triangles.
// Meshless: nodal integration, central differences; FEM: tet4, implicit
// Euler with one linearised solve a step (SOFA's scheme); both at 0.25 ms,
// within the nodal run's critical step at the full mode's 3 mm spacing. FEM
// assembles the definite tangent (solve.tangent: definite): with the exact
// one, the elements squeezed next to a remeshed cut made the matrix
// indefinite a few moves in and CHOLMOD stopped the run. Uncut runs of both
// give the sag without the cut. Each run writes a ParaView series
// (runs/<label>/cut.pvd: the body, the cut surface with its opening, and for
// the grid the Enrichment Grid's phi).
// Measured: each update's time (the grid's shape functions, a remesh with
// state transfer, a cell removal, a split with the state copied), the step time, the free end's sag, and the
// opening: the x-displacement of a point 4 mm behind the blade's plane minus
// that of a point 4 mm before it, on the top face at mid-width (4 mm: the
// gap `remove` leaves is a cell wide).
// Claims, as results/cuts.md says them: every run finishes and each cut
// follows every blade move; in each the cut opens (past twice the same
// method's uncut block's opening) and the end sags more than uncut; uncut,
// nodal and FEM sag alike (within 5%; 12% at the quick mode's 5 mm); cut,
// remesh sags less than cell removal and the meshless block most. (Split
// cells, whose jump ends about a cell short of the blade's lower edge, leave
// a thicker ligament: measured at 3 mm they sag less than remesh.)
#include <cmath>
#include <optional>

#include "studies/study_scenes.h"
#include "studies/study_support.h"

namespace kerf {
namespace {

constexpr double length = 0.06, width = 0.03, height = 0.02;  // m
constexpr double blade_x = 0.02, blade_bottom = 0.008;        // m
constexpr double probe_offset = 0.004;                        // m, either side of the blade

struct Way {
  std::string label;
  Method method;
  std::optional<FemCut> fem;  // none: meshless
  bool cut = true;
};

constexpr double blade_step = 0.002;                             // m, each move across the width
const int moves = static_cast<int>(std::lround(width / blade_step)) + 1;  // from y = -1 mm to 1 mm beyond

/// The blade's strip: a vertical edge at x = blade_x crossing the width in
/// `moves` moves from t = 0.1 s to 60% of the way to the end.
Cut blade(const Way& w, double duration) {
  Cut cut;
  cut.is_strip = true;
  for (int k = 0; k <= moves; ++k) {
    // As written: at 3 mm the blade's edge passes node rows (y = 9, 15, 21 mm),
    // and moves fall on steps' times (t = 0.22 s).
    const double y = study_scene::as_written(-0.5 * blade_step + blade_step * k);
    const double t = study_scene::as_written(0.1 + 0.6 * (duration - 0.1) * k / moves);
    cut.vertices.push_back(Vec3(blade_x, y, height + 0.001));
    cut.vertices.push_back(Vec3(blade_x, y, blade_bottom));
    cut.times.insert(cut.times.end(), 2, k == 0 ? 0.0 : t);
  }
  cut.enrichment = Enrichment::grid;
  cut.fem = w.fem.value_or(FemCut::remesh);
  return cut;
}

Scene scene_of(const Way& w, double spacing, double duration, int vtk_every) {
  using namespace study_scene;
  Scene scene = box_body("cut", Vec3(0, 0, 0), Vec3(length, width, height));
  scene.material = material(MaterialModel::corotational, 3.0e4, 0.35, 1000.0, 10.0);
  scene.discretization.method = w.method;
  scene.discretization.fem.size = spacing;
  scene.discretization.meshless.spacing = spacing;
  scene.boundary = {held(0, 0.0)};
  scene.gravity = Vec3(0, 0, -9.81);
  if (w.cut) scene.cuts = {blade(w, duration)};
  scene.solve = implicit_steps(0.00025, 1);
  scene.solve.duration = duration;
  if (w.method != Method::fem) scene.solve.integrator = Integrator::central_difference;
  scene.solve.tangent = TangentKind::definite;
  scene.output.vtk_every = vtk_every;
  scene.output.probes = {displacement_probe("end", Vec3(length, width / 2, height / 2)),
                         displacement_probe("behind", Vec3(blade_x + probe_offset, width / 2, height)),
                         displacement_probe("before", Vec3(blade_x - probe_offset, width / 2, height)),
                         energy_probe("energy")};
  return scene;
}

/// One way's run: its figures and its CSV row.
Json run_way(StudyRunner& runner, CsvTable& table, const Way& w, const Scene& scene) {
  const RunRecord run = runner.run(w.label, scene);
  const bool ok = run.ok();
  Json r = {{"status", ok ? std::string("ok") : run.error}};
  if (ok) {
    r["nodes"] = run.report.counts.nodes;
    r["updates"] = run.cut_update_ms.count;
    r["update_ms_median"] = run.cut_update_ms.median_ms;
    r["update_ms_max"] = run.cut_update_ms.max_ms;
    r["refresh_ms_median"] = run.cut_refresh_ms.median_ms;
    r["step_ms_median"] = run.step_ms.median_ms;
    r["end_sag_m"] = -run.probe("end", 2);
    r["opening_m"] = run.probe("behind", 0) - run.probe("before", 0);
    r["paraview"] = "runs/" + w.label + "/cut.pvd";
  }
  table.row({w.label, r.value("nodes", Json()), r.value("updates", Json()), r.value("update_ms_median", Json()),
             r.value("update_ms_max", Json()), r.value("step_ms_median", Json()), r.value("end_sag_m", Json()),
             r.value("opening_m", Json()), ok ? "ok" : "error"});
  return r;
}

void check_cut_claims(const std::vector<Way>& ways, Json& runs, bool quick) {
  for (const Way& w : ways)
    check_claim(runs[w.label]["status"] == "ok", w.label + " ran (" + runs[w.label]["status"].get<std::string>() + ")");
  for (const Way& w : ways) {
    const Json& r = runs[w.label];
    if (!w.cut) continue;
    const Json& uncut = runs[std::string(to_string(w.method)) + "_uncut"];
    check_claim(r["updates"].get<int>() == moves, w.label + " followed each of the blade's " + std::to_string(moves) +
                                                      " moves (it updated " + r["updates"].dump() + " times)");
    check_claim(r["opening_m"].get<double>() > 2.0 * std::abs(uncut["opening_m"].get<double>()),
                w.label + ": the cut opens past twice the uncut block's relative displacement");
    check_claim(r["end_sag_m"].get<double>() > uncut["end_sag_m"].get<double>(),
                w.label + ": the cut block's end sags more than the uncut block's");
  }
  auto sag = [&](const char* way) { return runs[way]["end_sag_m"].get<double>(); };
  const double uncut_gap = std::abs(sag("nodal_uncut") - sag("fem_uncut")) / sag("fem_uncut");
  const double agree = quick ? 0.12 : 0.05;  // 9.4% at the quick mode's 5 mm, 3.7% at 3 mm (measured)
  check_claim(uncut_gap < agree, "uncut, nodal and FEM sag alike: within " + std::to_string(agree) + " (they differ by " +
                                     std::to_string(uncut_gap) + ")");
  check_claim(sag("fem_remesh") < sag("fem_remove") && sag("fem_remove") < sag("nodal_grid"),
              "cut, the remeshed block sags less than with cells removed, the meshless one most (" +
                  std::to_string(sag("fem_remesh")) + " < " + std::to_string(sag("fem_remove")) + " < " +
                  std::to_string(sag("nodal_grid")) + " m)");
}

}  // namespace

void cut_study(const StudyOptions& options) {
  const bool quick = options.quick;
  const double spacing = quick ? 0.005 : 0.003;  // m
  const double duration = quick ? 0.3 : 1.5;    // s
  const int vtk_every = quick ? 400 : 80;
  const std::vector<Way> ways{
      {"nodal_grid", Method::nodal, std::nullopt},
      {"fem_remesh", Method::fem, FemCut::remesh},
      {"fem_remove", Method::fem, FemCut::remove},
      {"fem_split", Method::fem, FemCut::split},
      {"nodal_uncut", Method::nodal, std::nullopt, false},
      {"fem_uncut", Method::fem, std::nullopt, false},
  };
  StudyRunner runner("cut", options, static_cast<int>(ways.size()));
  CsvTable table(runner.out_dir() + "/cut.csv",
                 {"way", "nodes", "updates", "update_ms_median", "update_ms_max", "step_ms_median", "end_sag_m",
                  "opening_m", "status"});
  Json runs = Json::object();
  for (const Way& w : ways) runs[w.label] = run_way(runner, table, w, scene_of(w, spacing, duration, vtk_every));

  StudyResult result("cut", quick, {"cut.png"});
  for (const Way& w : ways) {
    if (!w.cut || runs[w.label]["status"] != "ok") continue;
    result.headline(w.label + ": median cut update", runs[w.label]["update_ms_median"], "ms");
    result.headline(w.label + ": opening 4 mm either side of the blade",
                    1e3 * runs[w.label]["opening_m"].get<double>(), "mm");
  }
  result["spacing_m"] = spacing;
  result["duration_s"] = duration;
  result["runs"] = runs;
  result.write(runner.out_dir());
  plot("cut", runner.out_dir());

  // The claims: what results/cuts.md says of the runs in words.
  check_cut_claims(ways, runs, quick);
}

}  // namespace kerf
