// A run that fails part-way stops with a message saying where and why, and
// leaves what it wrote readable: summary.json with the error, every probe row
// so far, and a ParaView series that VTK opens.
#include <gtest/gtest.h>
#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <filesystem>
#include <fstream>

#include "app/run_scene.h"
#include "core/check.h"
#include "support/test_support.h"

namespace kerf {
namespace {

using json = nlohmann::ordered_json;

// A very soft neo-Hookean block crushed by 40 g over 20 load steps: about a
// third of the way, the compressed block loses stability (the tangent stops
// being positive definite) and the run stops there.
const char* crushing = R"(
name: crush
domain: {box: {min: [0, 0, 0], max: [0.02, 0.02, 0.02]}}
material: {model: neohookean, young: 1000, poisson: 0.3, density: 1000}
discretization: {fem: {element: tet4, size: 0.01}}
boundary:
  - select: {plane: {axis: z, at: 0.0}}
    fix: [x, y, z]
body_force: {gravity: [0, 0, -400]}
solve: {analysis: static, load_steps: 20, newton: {max_iterations: 8}}
output:
  vtk: {every: 1}
  probes:
    - {name: top, point: [0.01, 0.01, 0.02], field: displacement}
)";

TEST(Failures, DivergingSolveStopsWithWhereAndWhyAndKeepsResultsReadable) {
  std::string dir = testing::output_directory("crush");
  Scene scene = testing::scene_from_text(crushing, {"output.dir=" + dir});
  std::string message;
  try {
    run_scene(scene, {"", true});
  } catch (const Error& e) {
    message = e.what();
  }
  ASSERT_FALSE(message.empty()) << "the crushing load did not fail";
  EXPECT_NE(message.find("static load step"), std::string::npos) << message;

  std::ifstream in(dir + "/summary.json");
  json summary = json::parse(in);
  EXPECT_EQ(summary["status"], "error");
  EXPECT_EQ(summary["error"], message);

  // Every completed load step left a probe row and a readable .vtu.
  std::ifstream csv(dir + "/probes.csv");
  std::string line;
  int rows = -1;
  while (std::getline(csv, line)) ++rows;
  ASSERT_GE(rows, 2) << "the run failed before writing a step";
  std::ifstream pvd(dir + "/crush.pvd");
  std::string text((std::istreambuf_iterator<char>(pvd)), std::istreambuf_iterator<char>());
  for (int k = 0; k < rows; ++k) {
    char name[64];
    std::snprintf(name, sizeof name, "crush_%04d.vtu", k);
    EXPECT_NE(text.find(name), std::string::npos) << name;
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName((dir + "/" + name).c_str());
    reader->Update();
    EXPECT_GT(reader->GetOutput()->GetNumberOfPoints(), 0) << name;
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << "left behind: " << entry.path();
}

// Central differences told to run above their critical step: refused by
// default, run when allowed, and then stopped by the divergence check with
// the step and time, the rows so far kept.
TEST(Failures, ExplicitRunAboveTheCriticalStepDivergesWithWhere) {
  const char* beam = R"(
name: unstable
domain: {box: {min: [0, 0, 0], max: [0.05, 0.01, 0.01]}}
material: {model: linear, young: 30000, poisson: 0.3, density: 1000}
discretization: {method: fem, fem: {element: tet4, size: 0.0025}}
boundary:
  - {select: {plane: {axis: x, at: 0}}, fix: [x, y, z]}
body_force: {gravity: [0, 0, -9.81]}
solve: {analysis: dynamic, integrator: central-difference, dt: 0.0012, duration: 2.4}
output: {vtk: false, probes: [{name: energy, field: energy}]}
)";
  const std::string dir = testing::output_directory("unstable_dt");
  testing::expect_mentions(
      testing::error_message([&] { run_scene(testing::scene_from_text(beam, {"output.dir=" + dir}), {"", true}); }),
      {"test.yaml", "solve.dt", "value 0.0012 s is above the critical time step", "expected dt <=",
       "solve.allow_unstable_dt"});
  std::string message;
  try {
    run_scene(testing::scene_from_text(beam, {"output.dir=" + dir, "solve.allow_unstable_dt=true"}), {"", true});
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("diverged"), std::string::npos) << message;
  EXPECT_NE(message.find("central-difference step"), std::string::npos) << message;
  std::ifstream in(dir + "/summary.json");
  const json summary = json::parse(in);
  EXPECT_EQ(summary["status"], "error");
  EXPECT_EQ(summary.value("diverged", false), true) << "a diverged run says so apart from its message";
  EXPECT_GT(summary["solver"]["critical_dt_s"].get<double>(), 0.0);
  EXPECT_LT(summary["solver"]["critical_dt_s"].get<double>(), 0.0012);
  std::ifstream csv(dir + "/probes.csv");
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_GT(rows, 10);
}

TEST(Failures, StaleFactorPreconditioningGivesTheSameSolutionAsFreshSolves) {
  // A corotational block swinging under gravity: CHOLMOD reuses its factor as
  // a preconditioner, Eigen's LDL^T (no reuse for this comparison) and
  // PETSc solve each matrix afresh.
  const char* swing = R"(
name: swing
domain: {box: {min: [0, 0, 0], max: [0.1, 0.02, 0.02]}}
material: {model: corotational, young: 2.0e4, poisson: 0.3, density: 1000}
discretization: {fem: {element: tet4, size: 0.01}}
boundary:
  - select: {plane: {axis: x, at: 0.0}}
    fix: [x, y, z]
body_force: {gravity: [0, 0, -9.81]}
solve: {analysis: dynamic, integrator: implicit-euler, dt: 0.01, duration: 0.3}
output:
  vtk: false
  probes:
    - {name: tip, point: [0.1, 0.01, 0.01], field: displacement}
)";
  auto tip = [&](const std::string& solver) {
    Scene scene = testing::scene_from_text(
        swing, {"solve.linear_solver=" + solver, "solve.petsc=-ksp_type preonly -pc_type cholesky",
                "output.dir=" + testing::output_directory("swing_" + solver)});
    json s = run_scene(scene, {"", true}).summary;
    return std::make_pair(s["probes"]["tip"]["displacement"][2].get<double>(), s.value("solver", json::object()));
  };
  auto [reused, reused_counters] = tip("cholmod");
  auto [fresh, fresh_counters] = tip("petsc");
  std::printf("tip: cholmod with reuse %.9e (%s), petsc fresh %.9e\n", reused, reused_counters.dump().c_str(), fresh);
  EXPECT_GT(std::abs(reused), 0.01) << "the bar should swing by centimetres (large rotations)";
  EXPECT_NEAR(reused, fresh, 1e-7 * std::abs(fresh));
  // The reuse path really ran: 105 linear solves (Newton iterations) on 8
  // factorizations (measured), the rest by CG preconditioned with a stale factor.
  const double factorizations = reused_counters["factorizations"].get<double>();
  const double solves = reused_counters["newton_iterations"].get<double>();
  EXPECT_GE(solves, 90);
  EXPECT_LE(factorizations, 10);
  EXPECT_LT(10 * factorizations, solves);
  EXPECT_GT(reused_counters["pcg_iterations"].get<double>(), solves);
}

}  // namespace
}  // namespace kerf
