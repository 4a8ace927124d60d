// Cuts end to end: the centre-cracked plate in plane strain with the crack as
// an enriched cut (nodal integration and EFG, every enrichment rule that a
// straight crack admits), against the same plate in FEM tri6 on a quarter
// model whose crack faces are free and whose ligament is on rollers.
#include <gtest/gtest.h>

#include "support/test_support.h"

namespace kerf {
namespace {

using json = nlohmann::ordered_json;

double opening(const json& s) {
  return s["probes"]["upper_face"]["displacement"][1].get<double>() -
         s["probes"]["lower_face"]["displacement"][1].get<double>();
}

TEST(CrackScenes, CentreCrackOpeningAgreesWithQuarterModelFemWithin3Percent) {
  json fem = testing::run_scene_file("scenes/crack_plate_2d_quarter_fem.yaml", {}, "crack_fem");
  ASSERT_EQ(fem["status"], "ok");
  const double reference = 2.0 * fem["probes"]["centre"]["displacement"][1].get<double>();
  // Griffith's infinite plate, 4 sigma a (1 - nu^2) / E, is below: the plate is finite.
  EXPECT_GT(reference, 4 * 1000 * 0.01 * (1 - 0.09) / 1e6);
  for (std::string method : {"nodal", "efg"})
    for (std::string rule : {"grid", "grid-interpolated", "single", "multiplicative"}) {
      const bool interpolated = rule == "grid-interpolated";
      json s = testing::run_scene_file("scenes/crack_plate_2d.yaml",
                                       {"discretization.method=" + method,
                                        "cuts.0.enrichment=" + (interpolated ? std::string("grid") : rule),
                                        std::string("cuts.0.grid.lookup=") + (interpolated ? "interpolated" : "exact"),
                                        "output.vtk=false"},
                                       "crack_" + method + "_" + rule);
      ASSERT_EQ(s["status"], "ok") << method << " " << rule;
      const double delta = opening(s);
      std::printf("crack opening %s %s: %.5e m, FEM %.5e m, difference %.2f%%\n", method.c_str(), rule.c_str(), delta,
                  reference, 100 * (delta - reference) / reference);
      EXPECT_NEAR(delta, reference, 0.03 * reference) << method << " " << rule;
    }
}

// Without the cut the same plate barely opens: the enrichment is what makes the crack.
TEST(CrackScenes, WithoutTheCutThePlateDoesNotOpen) {
  json s = testing::run_scene_file("scenes/crack_plate_2d.yaml", {"cuts=[]", "output.vtk=false"}, "crack_none");
  ASSERT_EQ(s["status"], "ok");
  EXPECT_LT(std::abs(opening(s)), 1e-3 * 4.2e-5);
}

}  // namespace
}  // namespace kerf
