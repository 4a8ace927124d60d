// Cuts end to end, against references: the centre-cracked plate in plane
// strain (2D, and a 3D slab held in plane strain) and a zigzag crack in the
// same plate, by every meshless enrichment rule and both FEM baselines
// (`fem: remesh`, `fem: remove`). References: FEM tri6 on a quarter model
// (straight crack), and fine `fem: remesh` of the whole plate (both cracks).
// The errors of every method are printed, and every row is asserted: the
// issue's 3% where a method meets it, elsewhere the level measured (in the
// comment beside it) with a margin, so that a regression fails.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <map>

#include "support/test_support.h"

namespace kerf {
namespace {

using json = nlohmann::ordered_json;

/// u(upper) - u(lower) of two displacement probes, x and y.
Eigen::Vector2d opening(const json& s, const std::string& upper = "upper_face",
                        const std::string& lower = "lower_face") {
  const json& p = s["probes"];
  return {p[upper]["displacement"][0].get<double>() - p[lower]["displacement"][0].get<double>(),
          p[upper]["displacement"][1].get<double>() - p[lower]["displacement"][1].get<double>()};
}

/// |delta - reference| / |reference|, printed with what it is.
double relative_error(const std::string& what, const Eigen::Vector2d& delta, const Eigen::Vector2d& reference) {
  const double error = (delta - reference).norm() / reference.norm();
  std::printf("%-44s opening [%.4e %.4e] m, reference [%.4e %.4e] m, error %.2f%%\n", what.c_str(), delta.x(),
              delta.y(), reference.x(), reference.y(), 100 * error);
  return error;
}

/// A scene file run without ParaView output, expected to end well.
constexpr auto& run_ok = testing::run_scene_file_ok;

/// The meshless rules by name: grid exact or interpolated, and the others.
std::vector<std::string> rule_overrides(const std::string& method, const std::string& rule) {
  const bool interpolated = rule == "grid-interpolated";
  return {"discretization.method=" + method, "cuts.0.enrichment=" + (interpolated ? std::string("grid") : rule),
          std::string("cuts.0.grid.lookup=") + (interpolated ? "interpolated" : "exact")};
}

/// `fem: remove` opens a gap one cell wide: only probes off the faces stay in the body.
const std::string straight_gap_probes =
    "output.probes=[{name: upper_gap, point: [0, 0.0015], field: displacement}, "
    "{name: lower_gap, point: [0, -0.0015], field: displacement}]";
const std::string kinked_gap_probes =
    "output.probes=[{name: upper_gap, point: [4.121e-4, 1.4423e-3], field: displacement}, "
    "{name: lower_gap, point: [-4.121e-4, -1.4423e-3], field: displacement}]";

double quarter_model_opening() {
  static const double reference = [] {
    // A folder of this process's own: ctest runs the tests that share this reference two at a time.
    json fem = run_ok("scenes/crack_plate_2d_quarter_fem.yaml", {}, "crack_fem_" + std::to_string(::getpid()));
    return 2.0 * fem["probes"]["centre"]["displacement"][1].get<double>();
  }();
  return reference;
}

TEST(CrackScenes, CentreCrackOpeningAgreesWithQuarterModelFemWithin3Percent) {
  const double reference = quarter_model_opening();
  // Griffith's infinite plate, 4 sigma a (1 - nu^2) / E, is below: the plate is finite.
  EXPECT_GT(reference, 4 * 1000 * 0.01 * (1 - 0.09) / 1e6);
  for (std::string method : {"nodal", "efg"})
    for (std::string rule : {"grid", "grid-interpolated", "single", "multiplicative"}) {
      json s = run_ok("scenes/crack_plate_2d.yaml", rule_overrides(method, rule), "crack_" + method + "_" + rule);
      const double error = relative_error("straight " + method + " " + rule, opening(s), {0.0, reference});
      EXPECT_LT(error, 0.03) << method << " " << rule;
    }
}

TEST(CrackScenes, FemBaselinesOnTheStraightCrack) {
  const double reference = quarter_model_opening();
  // Remesh: the whole plate, the crack embedded and opened, converges on the quarter model.
  const std::string fine_refine = "discretization.refine=[{box: {min: [-0.012, -0.003], max: [0.012, 0.003]}, size: 0.0001}]";
  json fine = run_ok("scenes/crack_plate_2d.yaml",
                     {"discretization.method=fem", "discretization.fem.element=tri6",
                      "discretization.fem.size=0.0005", fine_refine},
                     "crack_fem_remesh_fine");
  EXPECT_LT(relative_error("straight fem remesh tri6 0.5/0.1 mm", opening(fine), {0.0, reference}), 0.005);
  json coarse = run_ok("scenes/crack_plate_2d.yaml",
                       {"discretization.method=fem", "discretization.fem.element=tri6", "discretization.fem.size=0.001"},
                       "crack_fem_remesh");
  EXPECT_LT(relative_error("straight fem remesh tri6 1 mm", opening(coarse), {0.0, reference}), 0.03);
  // Remove: a gap a cell wide; first-order convergence at the probes off the faces.
  const Eigen::Vector2d gap_reference = opening(fine, "upper_gap", "lower_gap");
  double error_at[2];
  for (int i = 0; i < 2; ++i) {
    const std::string size = i == 0 ? "0.001" : "0.0005";
    json s = run_ok("scenes/crack_plate_2d.yaml",
                    {"discretization.method=fem", "discretization.fem.element=tri6", "discretization.fem.size=" + size,
                     "cuts.0.fem=remove", straight_gap_probes},
                    "crack_fem_remove_" + size);
    EXPECT_GT(s["solver"]["cut_removed_cells"].get<double>(), 0.0);
    error_at[i] = relative_error("straight fem remove tri6 " + size + " m (1.5 mm off)",
                                 opening(s, "upper_gap", "lower_gap"), gap_reference);
  }
  EXPECT_LT(error_at[0], 0.13);   // 10.5% measured
  EXPECT_LT(error_at[1], 0.055);  // 4.2% measured
  EXPECT_LT(error_at[1], 0.6 * error_at[0]) << "removal converges as the cells along the cut shrink";
}

// fem: split (copies of the cells the crack separates, the papers' front:
// the cells its tips pass through stay whole, so the jump ends about a cell
// short) converges at about order one in the cell size; the over-cut front
// (the tips' cells split too) brackets it from the other side at 2 mm.
// Measured (tri6): lag -18.2 / -7.1 / -3.8 / -2.1% at 2 / 1 / 0.5 / 0.25 mm,
// over +2.2 / -7.1 / -2.2 / -1.3%; remesh -1.9 / -0.9 / -0.3%.
TEST(CrackScenes, FemSplitOnTheStraightCrackConvergesAtOrderOne) {
  const Eigen::Vector2d reference(0.0, quarter_model_opening());
  const auto split = [&](const std::string& size, const std::string& front) {
    json s = run_ok("scenes/crack_plate_2d.yaml",
                    {"discretization.method=fem", "discretization.fem.element=tri6", "discretization.fem.size=" + size,
                     "discretization.fem.split_front=" + front, "cuts.0.fem=split"},
                    "crack_fem_split_" + front + "_" + size);
    EXPECT_GT(s["solver"]["cut_split_cells"].get<double>(), 0.0);
    EXPECT_GT(s["solver"]["cut_duplicated_nodes"].get<double>(), 0.0);
    return opening(s);
  };
  const double coarse = relative_error("straight fem split tri6 2 mm (lag)", split("0.002", "lag"), reference);
  const double middle = relative_error("straight fem split tri6 1 mm (lag)", split("0.001", "lag"), reference);
  const double fine = relative_error("straight fem split tri6 0.5 mm (lag)", split("0.0005", "lag"), reference);
  const Eigen::Vector2d over = split("0.002", "over");
  relative_error("straight fem split tri6 2 mm (over)", over, reference);
  EXPECT_LT(coarse, 0.20);
  EXPECT_LT(fine, 0.045);
  EXPECT_LT(fine, 0.6 * middle) << "lag converges at order of about one";
  EXPECT_LT(middle, 0.6 * coarse);
  EXPECT_GT(over.y(), reference.y()) << "the over-cut front brackets the answer at 2 mm";
}

// fem.split_front: subdivide: the tips' cells are subdivided so that the tip
// is a node, and the jump ends there: the split matches the conforming
// remesh's error at every size and converges faster than order one.
// Measured (tri6): -2.46 / -1.38 / -0.55 / -0.08% at 2 / 1 / 0.5 / 0.25 mm
// (lag -18.2 / -7.1 / -3.8 / -2.1%, remesh -1.9 / -0.9 / -0.3%). The 3D slab
// (tet10, against its remesh at 0.7 mm, 4.2329e-5 m): -1.61% at 2 mm (lag
// -16.9%, remesh -1.6%).
TEST(CrackScenes, FemSplitWithTheFrontSubdividedMatchesTheRemesh) {
  const Eigen::Vector2d reference(0.0, quarter_model_opening());
  const auto split = [&](const std::string& size) {
    json s = run_ok("scenes/crack_plate_2d.yaml",
                    {"discretization.method=fem", "discretization.fem.element=tri6", "discretization.fem.size=" + size,
                     "discretization.fem.split_front=subdivide", "cuts.0.fem=split"},
                    "crack_fem_split_subdivide_" + size);
    EXPECT_EQ(s["solver"]["cut_front_points"].get<int>(), 2) << "the two tips";
    EXPECT_EQ(s["solver"]["cut_front_unresolved"].get<int>(), 0);
    return opening(s);
  };
  const double coarse = relative_error("straight fem split tri6 2 mm (subdivide)", split("0.002"), reference);
  const double fine = relative_error("straight fem split tri6 0.5 mm (subdivide)", split("0.0005"), reference);
  EXPECT_LT(coarse, 0.03);
  EXPECT_LT(fine, 0.008);
  EXPECT_LT(fine, 0.5 * coarse) << "faster than order one";
  json slab = run_ok("scenes/crack_slab_3d.yaml",
                     {"discretization.method=fem", "cuts.0.fem=split", "discretization.fem.split_front=subdivide"},
                     "crack_slab_fem_split_subdivide");
  EXPECT_EQ(slab["solver"]["cut_front_unresolved"].get<int>(), 0);
  const double slab_reference = 4.2329e-5;  // m: tet10 remesh at 0.7 mm (results/cracks.md)
  EXPECT_LT(relative_error("slab 3D fem split tet10 2 mm (subdivide)", opening(slab), {0.0, slab_reference}), 0.02);
}

// The 3D slab in plane strain opens like the 2D plate: nodal and efg with the
// strip enriched by the grid, and fem remesh with the strip embedded (tet10).
TEST(CrackScenes, SlabOpeningAgreesWithThePlaneStrainPlateWithin3Percent) {
  const double reference = quarter_model_opening();
  const std::vector<std::pair<std::string, std::vector<std::string>>> runs = {
      {"nodal", {"discretization.method=nodal"}},
      {"efg", {"discretization.method=efg", "discretization.meshless.support=2.2"}},
      {"fem", {"discretization.method=fem"}}};
  for (const auto& [method, overrides] : runs) {
    json s = run_ok("scenes/crack_slab_3d.yaml", overrides, "crack_slab_" + method);
    EXPECT_LT(relative_error("slab 3D " + method, opening(s), {0.0, reference}), 0.03) << method;
  }
}

// Measured errors on the kinked crack at 1 mm: nodal grid 4.0%, interpolated
// 4.1%, multiplicative 4.5%, visibility 7.8%, diffraction 6.7%; efg grid 2.0%,
// interpolated 2.0%, multiplicative 1.9%, visibility 10.0%, diffraction 3.5%.
const std::map<std::string, double> kinked_bound = {
    {"nodal grid", 0.05},       {"nodal grid-interpolated", 0.05}, {"nodal multiplicative", 0.055},
    {"nodal visibility", 0.09}, {"nodal diffraction", 0.08},       {"efg grid", 0.03},
    {"efg grid-interpolated", 0.03}, {"efg multiplicative", 0.03}, {"efg visibility", 0.12},
    {"efg diffraction", 0.045}};

TEST(CrackScenes, KinkedCrackByEveryMethodAgainstFineRemesh) {
  json fine = run_ok("scenes/crack_kinked_2d_fem.yaml", {}, "kinked_fem_fine");
  const Eigen::Vector2d reference = opening(fine), gap_reference = opening(fine, "upper_gap", "lower_gap");
  for (std::string method : {"nodal", "efg"})
    for (std::string rule : {"grid", "grid-interpolated", "multiplicative", "visibility", "diffraction"}) {
      json s = run_ok("scenes/crack_kinked_2d.yaml", rule_overrides(method, rule), "kinked_" + method + "_" + rule);
      const double error = relative_error("kinked " + method + " " + rule, opening(s), reference);
      // The summary reports the moment matrices' conditioning, near the cut apart.
      const json& solver = s["solver"];
      EXPECT_GE(solver["mls_condition_median"].get<double>(), 1.0) << method << " " << rule;
      EXPECT_GE(solver["mls_condition_max"].get<double>(), solver["mls_condition_near_cut_max"].get<double>());
      EXPECT_GE(solver["mls_condition_near_cut_max"].get<double>(), solver["mls_condition_near_tip_max"].get<double>());
      EXPECT_GT(solver["mls_condition_near_tip_max"].get<double>(), 1.0) << method << " " << rule;
      // efg meets the 3% with the grid and multiplicative rules;
      // nodal integration with the MLS gradient at the nodes does not (4-8%);
      // visibility and diffraction bend the opening (8-10%). Smoothed
      // gradients converge (the test below).
      EXPECT_LT(error, kinked_bound.at(method + " " + rule)) << method << " " << rule;
    }
  json remesh = run_ok("scenes/crack_kinked_2d.yaml",
                       {"discretization.method=fem", "discretization.fem.element=tri6", "discretization.fem.size=0.001"},
                       "kinked_fem_remesh");
  EXPECT_LT(relative_error("kinked fem remesh tri6 1 mm", opening(remesh), reference), 0.03);
  json removed = run_ok("scenes/crack_kinked_2d.yaml",
                        {"discretization.method=fem", "discretization.fem.element=tri6",
                         "discretization.fem.size=0.001", "cuts.0.fem=remove", kinked_gap_probes},
                        "kinked_fem_remove");
  EXPECT_LT(relative_error("kinked fem remove tri6 1 mm (1.5 mm off)", opening(removed, "upper_gap", "lower_gap"),
                           gap_reference),
            0.13);  // 10.9% measured
}

// Nodal integration with the MLS gradient at the nodes (the paper's) does not
// converge near a crack: its error depends on where the lattice puts nodes
// next to the tips (measured 2-7% from 1 to 0.4 mm, not falling). Smoothed
// gradients (SCNI, meshless.gradient: smoothed) converge: within 3% at 0.5 mm
// on both cracks (measured 2.4% straight, 2.9% kinked; 2.7-4.2% at 1-0.586 mm).
TEST(CrackScenes, SmoothedNodalIntegrationConvergesWithin3PercentOnBothCracks) {
  const double straight = quarter_model_opening();
  json fine = run_ok("scenes/crack_kinked_2d_fem.yaml", {}, "kinked_fem_fine_smoothed");
  const Eigen::Vector2d kinked = opening(fine);
  for (std::string gradient : {"direct", "smoothed"}) {
    const std::vector<std::string> overrides = {"discretization.meshless.spacing=0.0005",
                                                "discretization.meshless.gradient=" + gradient};
    const double e_straight =
        relative_error("straight nodal " + gradient + " 0.5 mm",
                       opening(run_ok("scenes/crack_plate_2d.yaml", overrides, "straight_nodal_" + gradient)),
                       {0.0, straight});
    const double e_kinked =
        relative_error("kinked nodal " + gradient + " 0.5 mm",
                       opening(run_ok("scenes/crack_kinked_2d.yaml", overrides, "kinked_nodal_" + gradient)), kinked);
    // Direct: 5.7% straight, 6.1% kinked measured; smoothed: the 3%.
    EXPECT_LT(e_straight, gradient == "smoothed" ? 0.03 : 0.07) << gradient;
    EXPECT_LT(e_kinked, gradient == "smoothed" ? 0.03 : 0.075) << gradient;
  }
}

// Without the cut the same plate barely opens: the enrichment is what makes the crack.
TEST(CrackScenes, WithoutTheCutThePlateDoesNotOpen) {
  json s = run_ok("scenes/crack_plate_2d.yaml", {"cuts=[]"}, "crack_none");
  EXPECT_LT(std::abs(opening(s).y()), 1e-3 * 4.2e-5);
}

}  // namespace
}  // namespace kerf
