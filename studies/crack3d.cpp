// Crack convergence in 3D: the centre-cracked slab of scenes/crack_slab_3d.yaml
// (4.1 x 8.1 cm, 2 mm thick and held in plane strain by its faces, a crack of
// 2 cm through the thickness as a triangle strip, 1 kPa pulling it open),
// every method refined against a converged conforming reference (issue 19).
//
//   kerf study crack3d [--quick] [--out DIR]
//
// Measured: the crack's opening (u_y above minus below the crack faces) at
// its centre, and 1 mm behind its front (x = 9 mm, the front at 10 mm) on the
// slab's mid-plane and on one of its faces: in plane strain the opening does
// not vary along the front, so the face against the mid-plane is the 3D
// discretization's own error. `fem: remove` deletes the cells the crack
// crosses: it is measured 1.5 mm off the crack (both centre and front) and
// compared with the reference at those points.
// 1. The reference: `fem: remesh` tet10 with both crack tips refined to a
//    quarter of the element size (2 to 0.7 mm) until the two finest levels
//    agree to 0.5%; it is also compared with the independent 2D plane-strain
//    quarter model (scenes/crack_plate_2d_quarter_fem.yaml).
// 2. Each method at six levels (2 to 0.6 mm; tet10 without refinement to 0.8
//    mm) against it, with the observed order: nodal integration with direct
//    (the cells at the crack split, kerf's default; and whole, the paper's)
//    and smoothed gradients, EFG (support 2.2 as the regression
//    test uses; the scene's 2.8 costs 7x), `fem: remesh` tet4 and tet10,
//    `fem: remove` tet4, and `fem: split` tet10 with the front's cells
//    subdivided (uniform and with the tips refined). The supports hold the ends 1 mm either side of the
//    crack's plane (the scene: 0.6 mm, which holds no whole face of EFG's
//    background mesh above 1 mm). The meshless lattices at these spacings have an odd
//    number of intervals across the plate, so no node lies on the crack (the
//    cut_convergence study measures what nodes on a cut do).
// Quick mode runs 2 mm only and holds each method's errors to at most what the
// full study measured there (the constants below, from
// results/crack3d/crack3d.json): a one-sided bound an improvement passes.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/check.h"
#include "problem/scene_reader.h"
#include "studies/study_scenes.h"
#include "studies/study_support.h"

namespace kerf {
namespace {

constexpr double front_x = 0.009;     // m: 1 mm behind the crack's front at x = 10 mm
constexpr double face_z = 0.001;      // m: the slab's face
constexpr double gap_y = 0.0015;      // m: fem: remove's probes, off the deleted band
// The supports' patches on the slab's ends (the scene's 0.6 mm): tall enough to
// hold a whole facet of EFG's background mesh at every spacing here.
constexpr double support_half_height = 0.001;  // m
const std::vector<double> reference_sizes{0.002, 0.0014, 0.001, 0.0007};  // m; the last is the reference
const std::vector<double> levels{0.002, 0.0016, 0.00125, 0.001, 0.0008, 0.0006};  // m

// The full study's reference (tet10, tips refined, 0.7 mm) and each method's
// errors at 2 mm, in percent, as committed in results/crack3d/crack3d.json.
// The full mode checks that its reference still equals these. Made by
// `kerf study crack3d` (full) at f95bc61 (2026-11-24), EFG's rows re-made by
// the same at 7c92754 (2026-11-27); later rows say where they come from.
// ctest checks the quick mode at 1 and 2 threads.
struct Openings {
  double centre, front, gap_centre, gap_front;  // m
};
constexpr Openings reference_openings{4.256998e-05, 1.846745e-05, 4.375895e-05, 1.970963e-05};
struct QuickBound {
  const char* method;
  double centre_error, front_error;  // % at 2 mm
};
constexpr QuickBound measured_at_2mm[] = {
    {"fem_tet10_tips", -0.39, -1.30}, {"fem_tet10_remesh", -2.22, -8.43}, {"fem_tet4_remesh", -8.69, -41.23},
    {"fem_tet4_remove", 9.11, 13.95}, {"efg", 0.01, 10.18},           {"nodal_smoothed", 6.23, 27.51},
    {"nodal_direct_whole", 2.50, 6.51}, {"efg_tips", -1.08, -1.87},       {"nodal_smoothed_tips", 1.80, 5.37},
    // Direct nodal integration with the cells at the crack split (the default
    // since 2026-11-27), measured by `kerf study crack3d --quick` at 3db80fe:
    // the full study predates it.
    {"nodal_direct", -0.66, -1.73},   {"nodal_direct_tips", -0.42, 2.57},
    // fem: split with the front's cells subdivided (issue 36), measured at
    // 5558db5 by `kerf run` on the study's own scenes (its quick mode writes
    // them under scenes/): the full study predates them.
    {"fem_tet10_split_subdivide", -2.19, -13.74}, {"fem_tet10_split_subdivide_tips", -0.44, -2.40},
};
constexpr double quick_margin = 0.3;  // percentage points: the same scene, summed in another order

struct SlabMethod {
  std::string label;
  std::function<void(Scene&)> configure;  // on scenes/crack_slab_3d.yaml, beside the spacing
  std::vector<double> spacings;           // m, coarse to fine (full mode)
  bool meshless = false, removes_cells = false;
  double tip_refinement = 0;  // > 0: boxes around the tips at spacing / tip_refinement
};

std::vector<SlabMethod> study_methods() {
  const std::vector<double> tet10_levels(levels.begin(), levels.end() - 1);
  const std::vector<double> tips_levels{0.002, 0.00125, 0.001};
  auto fem = [](ElementType element, FemCut cut, SplitFront front) {
    return [=](Scene& s) {
      s.discretization.method = Method::fem;
      s.discretization.fem.element = element;
      s.discretization.fem.split_front = front;
      s.cuts[0].fem = cut;
    };
  };
  auto tet10 = fem(ElementType::tet10, FemCut::remesh, SplitFront::lag);
  auto split = fem(ElementType::tet10, FemCut::split, SplitFront::subdivide);
  auto efg = [](Scene& s) {
    s.discretization.method = Method::efg;
    s.discretization.meshless.support = 2.2;
  };
  auto nodal = [](NodalGradient gradient, CutCells cells) {
    return [=](Scene& s) {
      s.discretization.method = Method::nodal;
      s.discretization.meshless.gradient = gradient;
      s.discretization.meshless.cut_cells = cells;
    };
  };
  auto smoothed = nodal(NodalGradient::smoothed, CutCells::automatic);
  auto direct = nodal(NodalGradient::direct, CutCells::automatic);
  return {
      {"fem_tet10_tips", tet10, reference_sizes, false, false, 4},
      {"fem_tet10_remesh", tet10, tet10_levels},
      {"fem_tet4_remesh", fem(ElementType::tet4, FemCut::remesh, SplitFront::lag), levels},
      // Split cells (fem: split), the front's cells subdivided so that the jump ends on the tips.
      {"fem_tet10_split_subdivide", split, tet10_levels},
      {"fem_tet10_split_subdivide_tips", split, tips_levels, false, false, 4},
      {"fem_tet4_remove", fem(ElementType::tet4, FemCut::remove, SplitFront::lag), levels, false, true},
      {"efg", efg, levels, true},
      {"nodal_smoothed", smoothed, levels, true},
      {"nodal_direct", direct, levels, true},
      // The paper's: every node's whole cell at its node, across the crack too.
      {"nodal_direct_whole", nodal(NodalGradient::direct, CutCells::whole), levels, true},
      // The meshless lattices with the tips refined too (their own lattice at
      // half the spacing: a quarter, as the reference has, makes EFG's
      // stiffness singular at 1 mm).
      {"efg_tips", efg, tips_levels, true, false, 2},
      {"nodal_smoothed_tips", smoothed, tips_levels, true, false, 2},
      {"nodal_direct_tips", direct, tips_levels, true, false, 2},
  };
}

/// Pairs of probes either side of the crack at (x, +-y, z), named NAME_up and NAME_down.
void add_probe_pair(Scene& scene, const std::string& name, double x, double y, double z) {
  scene.output.probes.push_back(study_scene::displacement_probe(name + "_up", Vec3(x, y, z)));
  scene.output.probes.push_back(study_scene::displacement_probe(name + "_down", Vec3(x, -y, z)));
}

/// The slab by `m` at level `h`: its supports' patches, the tips' boxes, the
/// probes (on the faces unless the method removes cells).
Scene slab_scene(const SlabMethod& m, double h) {
  Scene scene = read_scene(study_data_path("scenes/crack_slab_3d.yaml"));
  m.configure(scene);
  (m.meshless ? scene.discretization.meshless.spacing : scene.discretization.fem.size) = h;
  for (const auto& [item, x] : {std::pair{4, -0.0205}, std::pair{5, 0.0205}}) {
    Selection& patch = scene.boundary[item].select;
    patch.kind = Selection::Kind::box;
    patch.box = Box{Vec3(x, -support_half_height, -0.001), Vec3(x, support_half_height, 0.001)};
  }
  if (m.tip_refinement > 0)
    for (double tip : {-0.01, 0.01})
      scene.discretization.refine.push_back(
          {Box{Vec3(study_scene::as_written(tip - 0.0015), -0.0015, -0.001),
               Vec3(study_scene::as_written(tip + 0.0015), 0.0015, 0.001)},
           h / m.tip_refinement});
  scene.output.probes.clear();
  add_probe_pair(scene, "gap_centre", 0, gap_y, 0);
  add_probe_pair(scene, "gap_front", front_x, gap_y, 0);
  if (!m.removes_cells) {
    add_probe_pair(scene, "centre", 0, 1e-9, 0);
    add_probe_pair(scene, "front_mid", front_x, 1e-9, 0);
    add_probe_pair(scene, "front_face", front_x, 1e-9, face_z);
  }
  scene.output.vtk_every = 0;
  return scene;
}

double opening_of(const RunRecord& run, const std::string& name) {
  return run.probe(name + "_up", 1) - run.probe(name + "_down", 1);
}

/// How far the uniform lattice's nearest column of nodes lies from the crack's
/// tips (x = +-10 mm), in x-spacings (node_set.cpp's rule: round(length / h)
/// intervals along each side); nodal integration is sensitive to it.
double tip_offset(double h) {
  constexpr double plate = 0.041, tip_from_edge = 0.0105;  // m
  const double spacing = plate / static_cast<double>(std::lround(plate / h));
  const double f = std::fmod(tip_from_edge / spacing, 1.0);
  return std::min(f, 1.0 - f);
}

/// One run's figures (errors filled in once the reference is known).
Json point_of(const SlabMethod& m, double h, const RunRecord& run) {
  Json p = {{"method", m.label}, {"spacing_m", h}, {"status", run.ok() ? std::string("ok") : run.error}};
  if (!run.ok()) return p;
  p["nodes"] = run.report.counts.nodes;
  p["dofs"] = run.report.counts.dofs;
  p["gap_centre_m"] = opening_of(run, "gap_centre");
  p["gap_front_m"] = opening_of(run, "gap_front");
  if (!m.removes_cells) {
    p["centre_m"] = opening_of(run, "centre");
    p["front_mid_m"] = opening_of(run, "front_mid");
    p["front_face_m"] = opening_of(run, "front_face");
  }
  p["run_s"] = whole_run_seconds(run);
  if (m.meshless && m.tip_refinement == 0) p["tip_offset"] = tip_offset(h);
  return p;
}

const Json& find_point(const Json& points, const std::string& method, double h) {
  for (const Json& p : points)
    if (p["method"] == method && p["spacing_m"] == h) return p;
  throw Error("crack3d: no point " + method + " at h = " + std::to_string(h));
}

/// Each point's errors against the reference: the opening at the centre and
/// behind the front (1.5 mm off the crack for fem: remove), and the front's
/// variation through the thickness (face against mid-plane; 0 in plane strain).
void add_errors(Json& points, const Openings& reference) {
  for (Json& p : points) {
    if (p["status"] != "ok") continue;
    if (p.contains("centre_m")) {
      p["centre_error_percent"] = percent_off(p["centre_m"], reference.centre);
      p["front_error_percent"] = percent_off(p["front_mid_m"], reference.front);
      p["front_through_thickness_percent"] = percent_off(p["front_face_m"], p["front_mid_m"]);
    } else {
      p["centre_error_percent"] = percent_off(p["gap_centre_m"], reference.gap_centre);
      p["front_error_percent"] = percent_off(p["gap_front_m"], reference.gap_front);
    }
  }
}

/// Each method's errors at its finest level and its observed order.
Json headline_of(const Json& points, const Json& orders) {
  Json headline = Json::array(), finest = Json::object();
  for (const Json& p : points)
    if (p.contains("centre_error_percent")) finest[p["method"].get<std::string>()] = p;  // spacings fall
  for (const auto& [method, p] : finest.items())
    headline.push_back({{"what", method + ": opening error at the centre at h = " + p["spacing_m"].dump() + " m" +
                                     (orders.contains(method) ? ", observed order " + orders[method]["centre"].dump()
                                                              : "")},
                        {"value", p["centre_error_percent"]}, {"unit", "%"}});
  return headline;
}

std::vector<double> spacings_of(const SlabMethod& m, bool quick) {
  return quick ? std::vector<double>{0.002} : m.spacings;
}

/// A method's points (coarse to fine) as they ran.
std::vector<Json> points_of(const Json& points, const std::string& method) {
  std::vector<Json> out;
  for (const Json& p : points)
    if (p["method"] == method) out.push_back(p);
  return out;
}

/// Does the centre's |error| fall from each level to the next (the last `skip` levels left out)?
bool falls_at_every_level(const std::vector<Json>& levels, std::size_t skip) {
  for (std::size_t i = 1; i + skip < levels.size(); ++i)
    if (std::abs(levels[i]["centre_error_percent"].get<double>()) >=
        std::abs(levels[i - 1]["centre_error_percent"].get<double>()))
      return false;
  return true;
}

/// What each method does under refinement (full mode), as results/cracks.md says it.
void check_method_claims(const Json& points) {
  for (const Json& p : points_of(points, "efg")) {
    const double h = p["spacing_m"], centre = p["centre_error_percent"], front = p["front_error_percent"];
    check_claim(std::abs(centre) < 3.0, "efg's opening at the centre is within 3 % at every level (" +
                                            std::to_string(centre) + " at h = " + std::to_string(h) + ")");
    if (h <= 0.00125)
      check_claim(std::abs(front) < 3.5, "efg's opening behind the front is within 3.5 % from 1.25 mm on (" +
                                             std::to_string(front) + " at h = " + std::to_string(h) + ")");
  }
  const std::vector<Json> tet4 = points_of(points, "fem_tet4_remesh");
  for (const Json& p : tet4)
    check_claim(p["centre_error_percent"].get<double>() < 0.0, "tet4 remesh is stiff at every level");
  check_claim(std::abs(tet4.back()["centre_error_percent"].get<double>()) <
                  0.5 * std::abs(tet4.front()["centre_error_percent"].get<double>()),
              "tet4 remesh's centre error halves from 2 to 0.6 mm");
  for (const Json& p : points_of(points, "fem_tet4_remove"))
    check_claim(p["centre_error_percent"].get<double>() > 3.0, "fem remove is more than 3 % soft at every level");
  for (const Json& p : points_of(points, "nodal_smoothed"))
    check_claim(p["centre_error_percent"].get<double>() > 2.0 && p["front_error_percent"].get<double>() > 9.0,
                "smoothed nodal integration is soft at every level (centre > 2 %, front > 9 %)");
  // The paper's direct nodal integration: no convergence, and its worst level
  // is the one whose nodes lie closest to the tips.
  const std::vector<Json> direct = points_of(points, "nodal_direct_whole");
  const auto worst = std::max_element(direct.begin(), direct.end(), [](const Json& a, const Json& b) {
    return std::abs(a["centre_error_percent"].get<double>()) < std::abs(b["centre_error_percent"].get<double>());
  });
  const auto nearest = std::min_element(direct.begin(), direct.end(), [](const Json& a, const Json& b) {
    return a["tip_offset"].get<double>() < b["tip_offset"].get<double>();
  });
  check_claim(worst == nearest, "the paper's direct nodal integration is furthest off where the lattice puts nodes nearest the "
                                "crack's tips (h = " + (*worst)["spacing_m"].dump() + " m)");
  const std::size_t w = static_cast<std::size_t>(worst - direct.begin());
  // Refining the tips as the reference does: tet10 falls at every level, the
  // meshless methods do not (at half the spacing; a quarter is singular for EFG).
  check_claim(falls_at_every_level(points_of(points, "fem_tet10_tips"), 1),
              "tet10 with the tips refined falls towards the reference at every level");
  for (const char* method : {"efg_tips", "nodal_smoothed_tips", "nodal_direct_tips"})
    check_claim(!falls_at_every_level(points_of(points, method), 0),
                std::string(method) + ": the meshless method with its tips refined does not fall at every level");
  check_claim(w > 0 && std::abs(direct[w]["centre_error_percent"].get<double>()) >
                           2.0 * std::abs(direct[w - 1]["centre_error_percent"].get<double>()),
              "the paper's direct nodal integration does not converge: its worst level is more than twice as far off "
              "as the coarser level before it");
  // With the cells at the crack split: within 2 % at the centre at every
  // level (measured at most 1.27, at 0.8 mm), and never further off than the paper's.
  const std::vector<Json> split = points_of(points, "nodal_direct");
  for (std::size_t i = 0; i < split.size() && i < direct.size(); ++i) {
    const double centre = split[i]["centre_error_percent"], whole = direct[i]["centre_error_percent"];
    check_claim(std::abs(centre) < 2.0 && std::abs(centre) <= std::abs(whole),
                "direct nodal integration with split cells is within 2 % at the centre and no further off than with "
                "whole cells (" + std::to_string(centre) + " against " + std::to_string(whole) + " % at h = " +
                    split[i]["spacing_m"].dump() + " m)");
  }
}

/// The claims, as results/cracks.md says them in words.
void check_crack3d_claims(const Json& result, bool quick) {
  const Json& points = result["points"];
  for (const Json& p : points)
    check_claim(p["status"] == "ok", p["method"].get<std::string>() + " at h = " + p["spacing_m"].dump() + " ran (" +
                                         p["status"].dump() + ")");
  for (const QuickBound& q : measured_at_2mm) {
    const Json& p = find_point(points, q.method, 0.002);
    const double centre = p["centre_error_percent"], front = p["front_error_percent"];
    check_claim(std::abs(centre) < std::abs(q.centre_error) + quick_margin &&
                    std::abs(front) < std::abs(q.front_error) + quick_margin,
                std::string(q.method) + " at 2 mm is off the reference by at most what the full study measured (centre " +
                    std::to_string(centre) + " % against " + std::to_string(q.centre_error) + ", front " +
                    std::to_string(front) + " % against " + std::to_string(q.front_error) + ")");
  }
  const Json& reference = result["reference"];
  const double plate = result["plane_strain_2d"]["centre_m"];
  check_claim(std::abs(percent_off(reference["centre_m"], plate)) < 0.1,
              "the 3D reference's opening at the centre is within 0.1 % of the 2D plane-strain quarter model's (" +
                  reference["centre_m"].dump() + " against " + std::to_string(plate) + " m)");
  if (quick) return;
  const Json& previous = find_point(points, "fem_tet10_tips", reference_sizes[reference_sizes.size() - 2]);
  for (const char* key : {"centre_m", "front_mid_m", "gap_centre_m", "gap_front_m"})
    check_claim(std::abs(percent_off(previous[key], reference[key])) < 0.5,
                std::string("the reference has converged: its two finest levels agree to 0.5 % in ") + key);
  const Openings& r = reference_openings;
  check_claim(std::abs(percent_off(r.centre, reference["centre_m"])) < 0.1 &&
                  std::abs(percent_off(r.front, reference["front_mid_m"])) < 0.1 &&
                  std::abs(percent_off(r.gap_centre, reference["gap_centre_m"])) < 0.1 &&
                  std::abs(percent_off(r.gap_front, reference["gap_front_m"])) < 0.1,
              "the reference equals the one quick mode uses (update reference_openings)");
  check_method_claims(points);
}

}  // namespace

void crack3d_study(const StudyOptions& options) {
  const bool quick = options.quick;
  const std::vector<SlabMethod> methods = study_methods();
  int planned = 1;
  for (const SlabMethod& m : methods) planned += static_cast<int>(spacings_of(m, quick).size());
  StudyRunner runner("crack3d", options, planned);

  // The independent check: the 2D plane-strain plate, a quarter by symmetry (its centre moves half the opening).
  const RunRecord plate =
      runner.run("plane_strain_2d_quarter", read_scene(study_data_path("scenes/crack_plate_2d_quarter_fem.yaml")));
  KERF_CHECK(plate.ok(), "crack3d: the 2D quarter model failed: ", plate.error);
  const double plate_opening = 2.0 * plate.probe("centre", 1);

  Json points = Json::array();
  for (const SlabMethod& m : methods)
    for (double h : spacings_of(m, quick)) {
      std::ostringstream label;
      label << m.label << "_h" << 1e3 * h << "mm";
      points.push_back(point_of(m, h, runner.run(label.str(), slab_scene(m, h))));
    }

  Json reference_point = {{"centre_m", reference_openings.centre}, {"front_mid_m", reference_openings.front},
                          {"gap_centre_m", reference_openings.gap_centre},
                          {"gap_front_m", reference_openings.gap_front}};
  if (!quick) {
    const Json& finest = find_point(points, methods[0].label, reference_sizes.back());
    KERF_CHECK(finest["status"] == "ok", "crack3d: the reference run failed: ", finest["status"].dump());
    reference_point = finest;
  }
  const Openings reference{reference_point["centre_m"], reference_point["front_mid_m"],
                           reference_point["gap_centre_m"], reference_point["gap_front_m"]};
  add_errors(points, reference);
  Json orders = Json::object();
  for (const SlabMethod& m : methods) {
    std::vector<double> h = spacings_of(m, quick);
    if (&m == &methods[0] && !quick) h.pop_back();  // the reference itself
    std::vector<Json> levels;
    for (double s : h) levels.push_back(find_point(points, m.label, s));
    const bool all_ran = std::all_of(levels.begin(), levels.end(), [](const Json& p) { return p["status"] == "ok"; });
    if (h.size() >= 2 && all_ran)
      orders[m.label] = observed_orders(levels, {{"centre", "centre_error_percent"}, {"front", "front_error_percent"}});
  }
  StudyResult result("crack3d", quick, {"crack3d.png"});
  result.set_headline(headline_of(points, orders));
  result["reference"] = {{"method", methods[0].label}, {"spacing_m", reference_sizes.back()},
                         {"tip_size_m", reference_sizes.back() / methods[0].tip_refinement},
                         {"centre_m", reference.centre}, {"front_mid_m", reference.front},
                         {"gap_centre_m", reference.gap_centre}, {"gap_front_m", reference.gap_front}};
  result["plane_strain_2d"] = {{"scene", "scenes/crack_plate_2d_quarter_fem.yaml"}, {"centre_m", plate_opening}};
  result["front_x_m"] = front_x;
  result["gap_y_m"] = gap_y;
  result["observed_order"] = orders;
  result["points"] = points;
  result.write(runner.out_dir());
  plot("crack3d", runner.out_dir());
  check_crack3d_claims(result.json(), quick);
}

}  // namespace kerf
