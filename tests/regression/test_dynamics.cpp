// Dynamic runs end to end: undamped Newmark conserves energy, central
// differences stay bounded just below the critical-step estimate and are
// refused above it, implicit Euler settles on the static solution.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "app/run_scene.h"
#include "discretization/body_capabilities.h"
#include "discretization/body_factory.h"
#include "problem/scene_reader.h"
#include "core/check.h"
#include "solvers/sparse_assembly.h"
#include "support/test_support.h"

namespace kerf {
namespace {

using json = nlohmann::ordered_json;

// A soft bar clamped at x = 0 under suddenly applied gravity.
const char* bar = R"(
name: bar
domain: {box: {min: [0, 0, 0], max: [0.1, 0.02, 0.02]}}
material: {model: linear, young: 1.0e5, poisson: 0.3, density: 1000.0}
discretization: {method: fem, fem: {element: tet4, size: 0.01}}
boundary:
  - select: {plane: {axis: x, at: 0.0}}
    fix: [x, y, z]
body_force: {gravity: [0, 0, -9.81]}
solve: {analysis: dynamic, integrator: newmark, dt: 0.001, duration: 1.0}
output:
  vtk: false
  probes:
    - {name: tip, point: [0.1, 0.01, 0.01], field: displacement}
    - {name: energy, field: energy}
)";

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  std::vector<double> column(const std::string& name) const {
    auto at = std::find(columns.begin(), columns.end(), name) - columns.begin();
    std::vector<double> values;
    for (const auto& r : rows) values.push_back(r.at(at));
    return values;
  }
};

Table read_csv(const std::string& path) {
  std::ifstream in(path);
  Table t;
  std::string line, cell;
  std::getline(in, line);
  std::stringstream header(line);
  while (std::getline(header, cell, ',')) t.columns.push_back(cell);
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::vector<double> values;
    while (std::getline(row, cell, ',')) values.push_back(std::stod(cell));
    t.rows.push_back(values);
  }
  return t;
}

Table run_bar(const std::vector<std::string>& overrides, const std::string& test) {
  std::vector<std::string> all = overrides;
  std::string dir = testing::output_directory(test);
  all.push_back("output.dir=" + dir);
  Scene scene = testing::scene_from_text(bar, all);
  RunOptions options;
  options.quiet = true;
  run_scene(scene, options);
  return read_csv(dir + "/probes.csv");
}

/// The critical step central differences use, as its run reports it.
double critical_step_of(const std::vector<std::string>& overrides) {
  std::vector<std::string> all = overrides;
  all.push_back("solve.integrator=central-difference");
  all.push_back("solve.dt=1e-6");
  all.push_back("solve.duration=1e-6");
  all.push_back("output.dir=" + testing::output_directory("critical_probe"));
  json s = run_scene(testing::scene_from_text(bar, all), {"", true}).summary;
  return s["solver"]["critical_dt_s"].get<double>();
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

TEST(Dynamics, UndampedNewmarkConservesEnergyOver1000Steps) {
  Table t = run_bar({"solve.newton.tolerance=1e-12"}, "newmark_energy");
  ASSERT_EQ(t.rows.size(), 1001u);
  auto total = t.column("energy_total");
  double scale = max_abs(t.column("energy_strain"));
  ASSERT_GT(scale, 0.0);
  double drift = 0.0;
  for (double e : total) drift = std::max(drift, std::abs(e - total.front()));
  std::printf("Newmark: max |E - E0| / max strain energy = %.3e over %zu steps\n", drift / scale, total.size() - 1);
  EXPECT_LT(drift / scale, 1e-6);
}

TEST(Dynamics, PlaneStrainNewmarkConservesEnergyToo) {
  std::string dir = testing::output_directory("plate_newmark");
  Scene scene = read_scene(testing::source_path("scenes/plate_tension_2d.yaml"),
                           {"solve.analysis=dynamic", "solve.integrator=newmark", "solve.dt=2e-4", "solve.duration=0.1",
                            "solve.newton.tolerance=1e-12", "output.vtk=false",
                            "output.probes.2={name: energy, field: energy}", "output.dir=" + dir});
  run_scene(scene, {"", true});
  Table t = read_csv(dir + "/probes.csv");
  auto total = t.column("energy_total");
  double scale = max_abs(t.column("energy_strain")), drift = 0.0;
  ASSERT_GT(scale, 0.0);
  for (double e : total) drift = std::max(drift, std::abs(e - total.front()));
  EXPECT_LT(drift / scale, 1e-6);
  // The suddenly applied traction makes the plate ring about the static stretch.
  EXPECT_GT(max_abs(t.column("corner_ux")), 1.5 * 0.91 * 1000 * 0.1 / 1e6);
}

TEST(Dynamics, CentralDifferencesStayBoundedJustBelowTheCriticalStep) {
  double dt = 0.98 * critical_step_of({});
  int steps = 5000;
  Table t = run_bar({"solve.integrator=central-difference", "solve.dt=" + std::to_string(dt),
                     "solve.duration=" + std::to_string(steps * dt), "output.vtk={every: 50}"},
                    "central_difference");
  auto tip = t.column("tip_uz");
  auto total = t.column("energy_total");
  double scale = max_abs(t.column("energy_strain"));
  double drift = 0.0;
  for (double e : total) drift = std::max(drift, std::abs(e - total.front()));
  // Under suddenly applied gravity the tip swings to twice the static sag at most.
  Table newmark = run_bar({}, "newmark_reference");
  double reference_swing = max_abs(newmark.column("tip_uz"));
  std::printf("central differences at 0.98 dt_crit (%.3e s): max tip %.3e m (Newmark %.3e m), energy drift %.3e\n",
              dt, max_abs(tip), reference_swing, drift / scale);
  EXPECT_LT(max_abs(tip), 1.2 * reference_swing);
  EXPECT_LT(drift / scale, 3e-5);  // 9.3e-6 measured
}

// The estimate is safe (never above 2 / omega_max of the assembled system,
// found here by plain power iteration) and tight; the element bound is safe.
TEST(Dynamics, CriticalStepEstimateIsSafeAndTight) {
  for (const char* element : {"tet4", "tet10"}) {
    Scene scene = testing::scene_from_text(bar, {std::string("discretization.fem.element=") + element});
    RunReport report;
    auto body = make_body(scene, report);
    SparseMatrix K = testing::assemble_stiffness(*body, Vector::Zero(body->dof_count()));
    Vector m = body->lumped_mass();
    FreeDofs free(body->dof_count(), body->dirichlet(0.0));
    // Power iteration on M^-1/2 K M^-1/2 over the free dofs.
    Vector s = m.cwiseSqrt().cwiseInverse(), x = Vector::Random(body->dof_count()), y;
    double omega2 = 0.0;
    for (int k = 0; k < 2000; ++k) {
      for (Index d = 0; d < x.size(); ++d)
        if (free.free_index(d) < 0) x[d] = 0.0;
      x.normalize();
      y = s.cwiseProduct(K * s.cwiseProduct(x));
      for (Index d = 0; d < y.size(); ++d)
        if (free.free_index(d) < 0) y[d] = 0.0;
      omega2 = x.dot(y);
      x = y;
    }
    double exact = 2.0 / std::sqrt(omega2);
    double estimate = critical_step_of({std::string("discretization.fem.element=") + element});
    double element_bound = capability<ElementStepBound>(*body)->critical_time_step();
    std::printf("%s: critical step %.4e s (element bound %.4e s), power iteration %.4e s (ratio %.4f)\n", element,
                estimate, element_bound, exact, estimate / exact);
    EXPECT_LE(estimate, exact * (1 + 1e-4));
    EXPECT_GE(estimate, 0.95 * exact);
    EXPECT_LE(element_bound, exact * (1 + 1e-6));
  }
}

TEST(Dynamics, CentralDifferencesAboveTheCriticalStepAreRefused) {
  double critical = critical_step_of({});
  Scene too_large = testing::scene_from_text(
      bar, {"solve.integrator=central-difference", "solve.dt=" + std::to_string(1.05 * critical),
            "output.dir=" + testing::output_directory("central_difference_refused")});
  try {
    run_scene(too_large, {"", true});
    FAIL() << "a step above the critical estimate was accepted";
  } catch (const Error& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("critical time step"), std::string::npos) << message;
    EXPECT_NE(message.find("solve.dt"), std::string::npos) << message;
  }
}

TEST(Dynamics, DampedImplicitEulerSettlesOnTheStaticSolution) {
  Table dynamic = run_bar({"solve.integrator=implicit-euler", "solve.dt=0.01", "solve.duration=3.0",
                           "material.damping.mass=20"},
                          "implicit_euler");
  Table statics = run_bar({"solve.analysis=static"}, "bar_static");
  double settled = dynamic.column("tip_uz").back(), expected = statics.column("tip_uz").back();
  EXPECT_NEAR(settled, expected, 1e-3 * std::abs(expected));
}

TEST(Dynamics, DampedCentralDifferencesSettleOnTheStaticSolution) {
  // Mass and stiffness damping; the stiffness part lowers the critical step.
  std::vector<std::string> damping = {"material.damping.mass=20", "material.damping.stiffness=2e-5"};
  double critical = critical_step_of(damping);
  double undamped = critical_step_of({});
  EXPECT_LT(critical, undamped);
  std::vector<std::string> run = damping;
  for (const char* s : {"solve.integrator=central-difference", "solve.duration=1.5", "output.vtk={every: 100}"})
    run.push_back(s);
  run.push_back("solve.dt=" + std::to_string(0.95 * critical));
  Table dynamic = run_bar(run, "damped_central_difference");
  Table statics = run_bar({"solve.analysis=static"}, "bar_static_reference");
  double settled = dynamic.column("tip_uz").back(), expected = statics.column("tip_uz").back();
  EXPECT_NEAR(settled, expected, 2e-3 * std::abs(expected));
}

TEST(Dynamics, OneLinearisedSolvePerStepMatchesFullNewtonForALinearBody) {
  Table one = run_bar({"solve.integrator=implicit-euler", "solve.newton.max_iterations=1", "solve.duration=0.1"},
                      "euler_one_solve");
  Table full = run_bar({"solve.integrator=implicit-euler", "solve.duration=0.1"}, "euler_full_newton");
  EXPECT_NEAR(one.column("tip_uz").back(), full.column("tip_uz").back(),
              1e-8 * std::abs(full.column("tip_uz").back()));
}

}  // namespace
}  // namespace kerf
