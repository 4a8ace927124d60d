// Organ study: the meshless methods on a curved body read from a gmsh mesh,
// against tet10 converged on the same geometry (issue 34: "right on any node
// set", not only on lattices in boxes).
//
//   kerf study organ [--quick] [--out DIR]
//
// The body: scenes/meshes/organ.geo, an ellipsoid with semi-axes 35 x 25 x
// 15 mm cut flat at z = -12 mm, linear (E = 5 kPa, nu = 0.35, 1000 kg/m^3),
// its base held, sagging under gravity, static: scenes/organ_sag.yaml with
// its mesh replaced. Measured: the z-displacement of the top (0, 0, 14.5) mm
// and of the end (33, 0, 0) mm, and the strain energy.
// 1. Meshes by gmsh from organ.geo, written into meshes/: first order at each
//    meshless size (the meshless nodes are the mesh's nodes), second order at
//    the reference's size.
// 2. The reference: tet10 at 1.5 mm (quick: 3 mm). At 2 mm it was 0.4 / 1.0
//    / 0.7 % stiffer than at 1.5 mm (results/organ_sag), so the reference is
//    within about 1 %.
// 3. Each meshless way at 4, 3 and 2 mm (quick: 4 mm): nodal integration at
//    its defaults (the paper's direct gradients with the hourglass term),
//    with NSNI, with NSNI and VCI, and EFG at its defaults (Nitsche's
//    essential conditions). Errors in percent against the reference, the
//    integration-constraint residual, set-up and solve time.
// Claims (full): every run finishes; EFG at its defaults within 3 % of the
// reference in all three at 2 mm and closer there than at 4 mm; nodal
// integration at its defaults and with NSNI closer in energy at every
// refinement; with NSNI and VCI within 3.5 % in energy at every size and
// closer than the defaults; VCI keeps the integration constraint (residual
// below 1e-10). Quick: every run finishes, VCI's residual, and NSNI with VCI
// closer than the defaults. Nodal integration at its defaults is not within
// 3 % (+10 / +14 / +13 % at 4 mm, measured): reported, not claimed.
#include <cmath>
#include <filesystem>
#include <sstream>

#include "core/check.h"
#include "geometry/gmsh_module.h"
#include "problem/scene_reader.h"
#include "studies/study_support.h"

namespace kerf {
namespace {

struct Way {
  std::string label;
  Method method;
  NodalStabilization stabilization = NodalStabilization::hourglass;
  VciOrder vci = VciOrder::none;
};

const std::vector<Way> ways{
    {"nodal", Method::nodal},
    {"nodal_nsni", Method::nodal, NodalStabilization::nsni},
    {"nodal_nsni_vci", Method::nodal, NodalStabilization::nsni, VciOrder::linear},
    {"efg", Method::efg},
};

/// organ.geo meshed by gmsh at `size` (m) and `order`, written to `path`.
void mesh_organ(const std::string& path, double size, int order) {
  gmsh_module().mesh_geo_file(study_data_path("scenes/meshes/organ.geo"), size, order, path);
}

/// scenes/organ_sag.yaml on `mesh` (an absolute path).
Scene organ_scene(const std::string& mesh) {
  Scene scene = read_scene(study_data_path("scenes/organ_sag.yaml"));
  scene.mesh_file = mesh;
  return scene;
}

Scene organ_scene(const std::string& mesh, const Way& w) {
  Scene scene = organ_scene(mesh);
  scene.discretization.method = w.method;
  scene.discretization.meshless.stabilization = w.stabilization;
  scene.discretization.meshless.vci = w.vci;
  return scene;
}

struct Figures {
  double top = 0, end = 0, energy = 0;
};
Figures figures(const RunRecord& run) {
  return {run.probe("top", 2), run.probe("end", 2), run.probe("energy", 1)};
}

/// One way at one mesh size against the reference: its point and its CSV row.
Json run_way(StudyRunner& runner, CsvTable& table, const Way& w, double size, const std::string& mesh,
             const Figures& ref) {
  std::ostringstream label;
  label << w.label << "_" << size * 1000 << "mm";
  const RunRecord run = runner.run(label.str(), organ_scene(mesh, w));
  const bool ok = run.ok();
  Json p = {{"way", w.label}, {"spacing_m", size}, {"status", ok ? "ok" : run.error}};
  if (ok) {
    const Figures f = figures(run);
    p["nodes"] = run.report.counts.nodes;
    p["top_error_percent"] = percent_off(f.top, ref.top);
    p["end_error_percent"] = percent_off(f.end, ref.end);
    p["energy_error_percent"] = percent_off(f.energy, ref.energy);
    p["ic_residual_max"] = run.extra("ic_residual_max");
    p["setup_s"] = run.report.setup_seconds;
    p["solve_s"] = run.report.solve_seconds;
  }
  table.row({p["way"], size, p.value("nodes", Json()), p.value("top_error_percent", Json()),
             p.value("end_error_percent", Json()), p.value("energy_error_percent", Json()),
             p.value("ic_residual_max", Json()), p.value("setup_s", Json()), p.value("solve_s", Json()), p["status"]});
  return p;
}

void check_organ_claims(const Json& points, const std::vector<double>& sizes, bool quick) {
  auto point = [&](const std::string& way, double size) -> const Json& {
    for (const Json& p : points)
      if (p["way"] == way && p["spacing_m"].get<double>() == size) return p;
    throw Error("organ study: no point " + way);
  };
  for (const Json& p : points)
    check_claim(p["status"] == "ok", p["way"].get<std::string>() + " at " + p["spacing_m"].dump() +
                                         " m runs (" + p["status"].get<std::string>() + ")");
  auto error = [&](const std::string& way, double size, const char* what) {
    return std::abs(point(way, size)[what].get<double>());
  };
  for (double size : sizes) {
    check_claim(point("nodal_nsni_vci", size)["ic_residual_max"].get<double>() < 1e-10,
                "VCI keeps the integration constraint on the organ's nodes (residual below 1e-10)");
    check_claim(error("nodal_nsni_vci", size, "energy_error_percent") < error("nodal", size, "energy_error_percent"),
                "nodal integration with NSNI and VCI is closer to the reference than at its defaults");
  }
  if (quick) return;
  const double fine = sizes.back(), coarse = sizes.front();
  for (const char* what : {"top_error_percent", "end_error_percent", "energy_error_percent"}) {
    check_claim(error("efg", fine, what) < 3.0, std::string("EFG at its defaults is within 3 % at 2 mm (") + what + ")");
    check_claim(error("efg", fine, what) < error("efg", coarse, what),
                std::string("EFG is closer at 2 mm than at 4 mm (") + what + ")");
  }
  for (const char* way : {"nodal", "nodal_nsni"})
    for (std::size_t i = 1; i < sizes.size(); ++i)
      check_claim(error(way, sizes[i], "energy_error_percent") < error(way, sizes[i - 1], "energy_error_percent"),
                  std::string(way) + " comes closer in energy at every refinement");
  // With VCI the energy's error stays near 3 % (2.7 / 3.1 / 3.0 %, measured):
  // what is left is the base held on nodal parameters (Nitsche removes it).
  for (double size : sizes)
    check_claim(error("nodal_nsni_vci", size, "energy_error_percent") < 3.5,
                "nodal integration with NSNI and VCI is within 3.5 % in energy at every size");
}

}  // namespace

void organ_study(const StudyOptions& options) {
  const bool quick = options.quick;
  const double reference_size = quick ? 0.003 : 0.0015;  // m
  const std::vector<double> sizes = quick ? std::vector<double>{0.004} : std::vector<double>{0.004, 0.003, 0.002};
  StudyRunner runner("organ", options, static_cast<int>(1 + ways.size() * sizes.size()));
  const std::string meshes = runner.out_dir() + "/meshes";
  std::filesystem::create_directories(meshes);
  auto mesh_file = [&](double size, int order) {
    std::ostringstream name;
    name << meshes << "/organ_" << size * 1000 << "mm_o" << order << ".msh";
    if (!std::filesystem::exists(name.str())) mesh_organ(name.str(), size, order);
    return std::filesystem::absolute(name.str()).string();
  };

  // 1. The reference.
  Scene reference_scene = organ_scene(mesh_file(reference_size, 2));
  reference_scene.discretization.method = Method::fem;
  reference_scene.discretization.fem.element = ElementType::tet10;
  const RunRecord ref_run = runner.run("tet10_reference", reference_scene);
  check_claim(ref_run.ok(), "the tet10 reference runs (" + ref_run.error + ")");
  const Figures ref = figures(ref_run);

  // 2. Each way at each size.
  CsvTable table(runner.out_dir() + "/organ.csv",
                 {"way", "size_m", "nodes", "top_error_percent", "end_error_percent", "energy_error_percent",
                  "ic_residual_max", "setup_s", "solve_s", "status"});
  Json points = Json::array();
  for (const Way& w : ways)
    for (double size : sizes) points.push_back(run_way(runner, table, w, size, mesh_file(size, 1), ref));
  StudyResult result("organ", quick, quick ? std::vector<std::string>{} : std::vector<std::string>{"organ.png"});
  for (const Json& p : points)
    if (p["status"] == "ok")
      result.headline(p["way"].get<std::string>() + " strain energy error at " + p["spacing_m"].dump() + " m",
                      p["energy_error_percent"], "%");
  result["reference"] = {{"element", "tet10"}, {"size_m", reference_size}, {"top_m", ref.top}, {"end_m", ref.end},
                         {"strain_energy_J", ref.energy}};
  result["points"] = points;
  result.write(runner.out_dir());

  if (!quick) plot("organ", runner.out_dir());

  // 3. Claims.
  check_organ_claims(points, sizes, quick);
}

}  // namespace kerf
