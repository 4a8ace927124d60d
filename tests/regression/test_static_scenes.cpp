// Static scenes end to end (scene file -> kerf run -> summary.json): the
// cantilever against beam theory, the plane-strain plate against its exact
// solution, reactions against the applied loads, and what a run builds.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/run_scene.h"
#include "problem/material.h"
#include "problem/scene_reader.h"
#include "core/check.h"
#include "support/test_support.h"

namespace kerf {
namespace {

using json = nlohmann::ordered_json;


// Euler-Bernoulli bending plus Timoshenko shear deflection of a cantilever
// of rectangular section b x h under its own weight q = rho g b h.
double beam_tip_deflection(double E, double nu, double rho, double g, double L, double b, double h) {
  double q = rho * g * b * h, I = b * h * h * h / 12.0, G = E / (2 * (1 + nu));
  double kappa = 10 * (1 + nu) / (12 + 11 * nu);
  return q * std::pow(L, 4) / (8 * E * I) + q * L * L / (2 * kappa * G * b * h);
}

TEST(StaticScenes, CantileverTet10MatchesBeamTheoryWithin3Percent) {
  json s = testing::run_scene_file("scenes/cantilever.yaml", {"discretization.fem.size=0.0025", "output.vtk=false"}, "cantilever_fine");
  ASSERT_EQ(s["status"], "ok");
  double w = -s["probes"]["tip"]["displacement"][2].get<double>();
  double beam = beam_tip_deflection(1e6, 0.3, 1000, 9.81, 0.1, 0.02, 0.02);
  std::printf("cantilever tet10: tip %.6e m, beam theory %.6e m, difference %.2f%%\n", w, beam,
              100 * (w - beam) / beam);
  EXPECT_NEAR(w, beam, 0.03 * beam);
  // The clamp carries the whole weight.
  EXPECT_NEAR(s["probes"]["support"]["reaction"][2].get<double>(), 1000 * 9.81 * 0.1 * 0.02 * 0.02, 1e-9);
}

TEST(StaticScenes, PlateInTensionHasTheExactPlaneStrainSolution) {
  json s = testing::run_scene_file("scenes/plate_tension_2d.yaml", {}, "plate");
  ASSERT_EQ(s["status"], "ok");
  // Uniform stress sigma_xx = 1000 Pa; plane strain: eps_xx = (1 - nu^2) sigma / E, eps_yy = -nu (1 + nu) sigma / E.
  const double E = 1e6, nu = 0.3, sigma = 1000, L = 0.1, H = 0.05;
  auto corner = s["probes"]["corner"]["displacement"];
  EXPECT_NEAR(corner[0].get<double>(), (1 - nu * nu) * sigma * L / E, 1e-10 * sigma * L / E);
  EXPECT_NEAR(corner[1].get<double>(), -nu * (1 + nu) * sigma * H / E, 1e-10 * sigma * L / E);
  EXPECT_NEAR(s["probes"]["support"]["reaction"][0].get<double>(), -sigma * H, 1e-9);
}

// fem.box_mesher: lattice: the box's lattice split into simplices by kerf,
// no gmsh (tests/startup/modules_on_demand.py checks that none is loaded,
// across processes: the modules list is the process's). Uniform tension on rollers is exact in every element
// (intervals of unequal lengths: 0.1 / 0.0045 and 0.05 / 0.0045 rounded), and
// the tet10 cantilever sags as on gmsh's mesh of the same size (-0.37% against
// -0.34% off the converged tip when written).
double tip_of(const json& s) { return s["probes"]["tip"]["displacement"][2].get<double>(); }

TEST(StaticScenes, LatticeMeshedBoxesPassThePatchTestInEveryElement) {
  const double E = 1e6, nu = 0.3, sigma = 1000, L = 0.1, H = 0.05;
  for (const char* element : {"tri3", "tri6"}) {
    json s = testing::run_scene_file("scenes/plate_tension_2d.yaml",
                                     {std::string("discretization.fem.element=") + element,
                                      "discretization.fem.size=0.0045", "discretization.fem.box_mesher=lattice",
                                      "output.vtk=false"},
                                     std::string("plate_lattice_") + element);
    ASSERT_EQ(s["status"], "ok") << element;
    auto corner = s["probes"]["corner"]["displacement"];
    EXPECT_NEAR(corner[0].get<double>(), (1 - nu * nu) * sigma * L / E, 1e-10 * sigma * L / E) << element;
    EXPECT_NEAR(corner[1].get<double>(), -nu * (1 + nu) * sigma * H / E, 1e-10 * sigma * L / E) << element;
    EXPECT_EQ(s["counts"]["nodes"].get<int>(), std::string(element) == "tri3" ? 23 * 12 : 45 * 23) << element;
  }
  // The same in 3D: a 3 x 2 x 1.5 cm block on rollers pulled along x (uniaxial stress).
  const std::string block = R"(
domain: {box: {min: [0, 0, 0], max: [0.03, 0.02, 0.015]}}
material: {model: linear, young: 1.0e6, poisson: 0.3}
discretization: {fem: {size: 0.004, box_mesher: lattice}}
boundary:
  - {select: {plane: {axis: x, at: 0.0}}, fix: [x]}
  - {select: {plane: {axis: y, at: 0.0}}, fix: [y]}
  - {select: {plane: {axis: z, at: 0.0}}, fix: [z]}
  - {select: {plane: {axis: x, at: 0.03}}, traction: [1000, 0, 0]}
solve: {analysis: static}
output:
  vtk: false
  probes: [{name: corner, point: [0.03, 0.02, 0.015], field: displacement}]
)";
  for (const char* element : {"tet4", "tet10"}) {
    Scene scene = testing::scene_from_text(block, {std::string("discretization.fem.element=") + element,
                                                   "output.dir=" + testing::output_directory(
                                                                       std::string("block_lattice_") + element)});
    json s = run_scene(scene, {"", true}).summary;
    ASSERT_EQ(s["status"], "ok") << element;
    auto corner = s["probes"]["corner"]["displacement"];
    const Vec3 exact(sigma * 0.03 / E, -nu * sigma * 0.02 / E, -nu * sigma * 0.015 / E);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(corner[i].get<double>(), exact[i], 1e-10 * exact[0]) << element << " " << i;
  }
  json gmsh = testing::run_scene_file("scenes/cantilever.yaml",
                                      {"discretization.fem.element=tet10", "output.vtk=false"},
                                      "cantilever_tet10_gmsh");
  json lattice = testing::run_scene_file("scenes/cantilever.yaml",
                                         {"discretization.fem.element=tet10", "discretization.fem.box_mesher=lattice",
                                          "output.vtk=false"},
                                         "cantilever_tet10_lattice");
  const double on_gmsh = tip_of(gmsh), on_lattice = tip_of(lattice);
  std::printf("cantilever tet10 at 5 mm: tip %.6e m on the lattice's mesh, %.6e m on gmsh's (%.3f%%)\n", on_lattice,
              on_gmsh, 100 * (on_lattice / on_gmsh - 1));
  EXPECT_NEAR(on_lattice, on_gmsh, 1e-3 * std::abs(on_gmsh));
}

// A bar on rollers stretched by 50% through a prescribed displacement: the
// exact solution is a homogeneous uniaxial stretch, which every element
// reproduces exactly (a nonlinear patch test). The reference comes from the
// material law: the lateral stretch l2 with P22(diag(l1, l2, l2)) = 0.
TEST(StaticScenes, LargeUniaxialStretchMatchesTheHomogeneousSolution) {
  const double H = 0.01, stretch = 1.5;  // bar 0.02 long, H x H section
  for (MaterialModel model_value : {MaterialModel::corotational, MaterialModel::stvk, MaterialModel::neohookean}) {
    const char* model = to_string(model_value);
    MaterialLaw law(Material{model_value, 1.0e4, 0.3, 1000.0, 0.0, 0.0});
    auto lateral_stress = [&](double l2) { return law.stress(Vec3(stretch, l2, l2).asDiagonal().toDenseMatrix())(1, 1); };
    double lo = 0.5, hi = 1.0;  // bisection on the lateral stretch
    for (int k = 0; k < 200; ++k) {
      double mid = 0.5 * (lo + hi);
      (lateral_stress(mid) > 0 ? hi : lo) = mid;
    }
    const double l2 = 0.5 * (lo + hi);
    const double force = law.stress(Vec3(stretch, l2, l2).asDiagonal().toDenseMatrix())(0, 0) * H * H;
    std::string yaml = R"(
domain: {box: {min: [0, 0, 0], max: [0.02, 0.01, 0.01]}}
material: {young: 1.0e4, poisson: 0.3}
discretization: {fem: {element: tet4, size: 0.005}}
boundary:
  - select: {plane: {axis: x, at: 0.0}}
    fix: [x]
  - select: {plane: {axis: y, at: 0.0}}
    fix: [y]
  - select: {plane: {axis: z, at: 0.0}}
    fix: [z]
  - select: {plane: {axis: x, at: 0.02}}
    displacement: [0.01, null, null]
solve: {analysis: static, load_steps: 4, newton: {tolerance: 1.0e-12}}
output:
  vtk: false
  probes:
    - {name: pull, select: {plane: {axis: x, at: 0.02}}, field: reaction}
    - {name: corner, point: [0.02, 0.01, 0.01], field: displacement}
)";
    Scene scene = testing::scene_from_text(yaml, {std::string("material.model=") + model,
                                                  "output.dir=" + testing::output_directory(std::string("stretch_") + model)});
    json s = run_scene(scene, {"", true}).summary;
    ASSERT_EQ(s["status"], "ok") << model;
    EXPECT_NEAR(s["probes"]["pull"]["reaction"][0].get<double>(), force, 1e-8 * force) << model;
    EXPECT_NEAR(s["probes"]["corner"]["displacement"][1].get<double>(), (l2 - 1) * H, 1e-10 * H) << model;
    std::printf("%s: 50%% stretch, force %.6f N (exact %.6f N), lateral stretch %.6f\n", model,
                s["probes"]["pull"]["reaction"][0].get<double>(), force, l2);
  }
}

TEST(StaticScenes, MeshFileSceneCarriesItsWeight) {
  json s = testing::run_scene_file("scenes/cube_from_mesh.yaml", {"output.vtk=false"}, "cube_from_mesh");
  ASSERT_EQ(s["status"], "ok");
  EXPECT_EQ(s["counts"]["nodes"], 337);
  EXPECT_NEAR(s["probes"]["base"]["reaction"][2].get<double>(), 1000 * 9.81 * 0.02 * 0.02 * 0.02, 1e-12);
  EXPECT_LT(s["probes"]["top"]["displacement"][2].get<double>(), 0.0);
}

TEST(StaticScenes, LinearCholmodRunBuildsNoMassAndNoPetsc) {
  json s = testing::run_scene_file("scenes/cantilever.yaml", {"discretization.fem.element=tet4", "discretization.fem.size=0.01",
                                          "output.vtk=false"}, "stages");
  auto stages = s["stages"].get<std::vector<std::string>>();
  auto has = [&](const char* name) { return std::find(stages.begin(), stages.end(), name) != stages.end(); };
  EXPECT_TRUE(has("mesh"));
  EXPECT_TRUE(has("stiffness"));
  EXPECT_TRUE(has("factorization"));
  EXPECT_FALSE(has("mass"));
  EXPECT_FALSE(has("petsc"));
  EXPECT_FALSE(has("vtk"));
}

// At a load a hundred times smaller (E = 100 MPa) every model is linear
// elasticity: each within 1e-3 of beam theory's share the linear model gets
// on this coarse tet10 mesh, itself within 3% of beam theory.
TEST(StaticScenes, NonlinearMaterialsConvergeAndAgreeAtSmallLoads) {
  const double beam = beam_tip_deflection(1e8, 0.3, 1000, 9.81, 0.1, 0.02, 0.02);
  auto tip = [](const char* model) {
    json s = testing::run_scene_file("scenes/cantilever.yaml",
                                     {"material.model=" + std::string(model), "material.young=1e8",
                                      "discretization.fem.size=0.01", "output.vtk=false"},
                                     std::string("small_load_") + model);
    EXPECT_EQ(s["status"], "ok") << model;
    return -s["probes"]["tip"]["displacement"][2].get<double>();
  };
  const double linear = tip("linear");
  EXPECT_NEAR(linear, beam, 0.03 * beam);
  for (const char* model : {"corotational", "stvk", "neohookean"}) EXPECT_NEAR(tip(model), linear, 1e-3 * linear) << model;
}

TEST(StaticScenes, PetscSolverAgreesWithCholmod) {
  std::vector<std::string> common = {"discretization.fem.element=tet4", "discretization.fem.size=0.005",
                                     "output.vtk=false"};
  json direct = testing::run_scene_file("scenes/cantilever.yaml", common, "cholmod");
  auto petsc_options = common;
  petsc_options.push_back("solve.linear_solver=petsc");
  petsc_options.push_back("solve.petsc=-ksp_type cg -pc_type gamg -ksp_rtol 1e-12");
  json petsc = testing::run_scene_file("scenes/cantilever.yaml", petsc_options, "petsc");
  ASSERT_EQ(petsc["status"], "ok");
  double a = direct["probes"]["tip"]["displacement"][2].get<double>();
  double b = petsc["probes"]["tip"]["displacement"][2].get<double>();
  EXPECT_NEAR(a, b, 1e-8 * std::abs(a));
  auto stages = petsc["stages"].get<std::vector<std::string>>();
  EXPECT_NE(std::find(stages.begin(), stages.end(), "petsc"), stages.end());
}

TEST(StaticScenes, MisspelledPetscOptionIsReported) {
  try {
    testing::run_scene_file("scenes/cantilever.yaml",
        {"discretization.fem.element=tet4", "discretization.fem.size=0.01", "output.vtk=false",
         "solve.linear_solver=petsc", "solve.petsc=-ksp_typo cg"},
        "petsc_typo");
    FAIL() << "a misspelled PETSc option was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("-ksp_typo"), std::string::npos) << e.what();
  }
  // The summary of the failed run says why.
  std::ifstream in(testing::output_path("petsc_typo") + "/summary.json");
  json s = json::parse(in);
  EXPECT_EQ(s["status"], "error");
  EXPECT_NE(s["error"].get<std::string>().find("ksp_typo"), std::string::npos);
}

TEST(StaticScenes, EveryLinearBackendGivesTheSameAnswer) {
  std::vector<double> tips;
  for (const char* solver : {"cholmod", "ldlt", "cg"}) {
    json s = testing::run_scene_file("scenes/cantilever.yaml",
                 {"discretization.fem.element=tet4", "discretization.fem.size=0.01", "output.vtk=false",
                  std::string("solve.linear_solver=") + solver},
                 std::string("backend_") + solver);
    tips.push_back(s["probes"]["tip"]["displacement"][2].get<double>());
  }
  EXPECT_NEAR(tips[1], tips[0], 1e-9 * std::abs(tips[0]));
  EXPECT_NEAR(tips[2], tips[0], 1e-7 * std::abs(tips[0]));
}

}  // namespace
}  // namespace kerf
