// summary.json read back typed (read_outcome): every figure a run reports
// comes back as the run held it, from a real run's file; a failed run's
// status, message and divergence; a folder with no summary is refused by name.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/run_scene.h"
#include "app/summary_json.h"
#include "core/check.h"
#include "support/test_support.h"

namespace kerf {
namespace {

// A growing cut through an explicit nodal block with every kind of probe
// a run can have without contact: the record's sections all filled.
constexpr const char* probed_cut_scene = R"(
name: record
domain: {box: {min: [0, 0, 0], max: [0.03, 0.02, 0.02]}}
material: {model: corotational, young: 3000.0, poisson: 0.3, density: 1000.0}
discretization: {method: nodal, meshless: {spacing: 0.005}}
boundary:
  - {select: {plane: {axis: x, at: 0}}, fix: [x, y, z]}
body_force: {gravity: [0, 0, -9.81]}
cuts:
  - strip: [[0.015, -0.001, 0.021], [0.015, -0.001, 0.012], [0.015, 0.021, 0.021], [0.015, 0.021, 0.012]]
    times: [0, 0, 0.002, 0.002]
solve: {analysis: dynamic, integrator: central-difference, dt: 0.0002, duration: 0.004}
output:
  vtk: false
  probes:
    - {name: tip, point: [0.03, 0.01, 0.01], field: displacement}
    - {name: held, select: {plane: {axis: x, at: 0}}, field: reaction}
    - {name: energy, field: energy}
)";

TEST(RunRecord, ASummaryReadsBackAsTheRunReportedIt) {
  RunOptions options;
  options.out_dir = testing::output_directory("record");
  options.quiet = true;
  const RunOutcome run = run_scene(testing::scene_from_text(probed_cut_scene), options);
  const RunRecord record = read_outcome(run.directory);

  EXPECT_TRUE(record.ok());
  EXPECT_EQ(record.directory, run.directory);
  const RunReport& a = run.report;
  const RunReport& b = record.report;
  EXPECT_EQ(b.counts.nodes, a.counts.nodes);
  EXPECT_EQ(b.counts.dofs, a.counts.dofs);
  EXPECT_EQ(b.counts.elements, a.counts.elements);
  EXPECT_EQ(b.counts.neighbors_mean, a.counts.neighbors_mean);
  EXPECT_EQ(b.setup_seconds, a.setup_seconds);
  EXPECT_EQ(b.solve_seconds, a.solve_seconds);
  for (std::size_t p = 0; p < phase_names.size(); ++p)
    EXPECT_EQ(b.phases.seconds(Phase(p)), a.phases.seconds(Phase(p))) << phase_names[p];
  EXPECT_EQ(b.stages, a.stages);
  EXPECT_EQ(b.solver.critical_dt_s, a.solver.critical_dt_s);
  ASSERT_TRUE(a.solver.critical_dt_s.has_value());
  EXPECT_EQ(b.cuts.updated_nodes, a.cuts.updated_nodes);
  EXPECT_GT(b.cuts.updated_nodes, 0);
  EXPECT_EQ(b.extras, a.extras);
  EXPECT_FALSE(b.extras.empty());  // the MLS conditioning
  EXPECT_EQ(record.step_ms.count, static_cast<long>(a.step_seconds.size()));
  EXPECT_EQ(record.cut_update_ms.count, static_cast<long>(a.cut_update_seconds.size()));
  EXPECT_GT(record.cut_update_ms.count, 0);

  const nlohmann::ordered_json& probes = run.summary["probes"];
  EXPECT_EQ(record.probes.at("tip").field, ProbeField::displacement);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(record.probe("tip", i), probes["tip"]["displacement"][i].get<double>());
    EXPECT_EQ(record.probe("held", i), probes["held"]["reaction"][i].get<double>());
  }
  EXPECT_EQ(record.probes.at("energy").field, ProbeField::energy);
  EXPECT_EQ(record.probe("energy", 3), probes["energy"]["total"].get<double>());
  testing::expect_mentions(testing::error_message([&] { record.probe("nowhere"); }), {"nowhere", "summary.json"});
  testing::expect_mentions(testing::error_message([&] { record.probe("tip", 3); }), {"tip", "3"});
}

TEST(RunRecord, ADivergedRunReadsBackAsDiverged) {
  RunOptions options;
  options.out_dir = testing::output_directory("blown_up");
  options.quiet = true;
  const Scene scene = testing::scene_from_text(probed_cut_scene, {"solve.dt=0.05", "solve.allow_unstable_dt=true",
                                                                  "solve.duration=10", "cuts=[]"});
  EXPECT_THROW(run_scene(scene, options), Diverged);
  const RunRecord record = read_outcome(options.out_dir);
  EXPECT_EQ(record.status, RunStatus::error);
  EXPECT_TRUE(record.diverged);
  EXPECT_NE(record.error.find("NaN"), std::string::npos) << record.error;
}

TEST(RunRecord, AFolderWithoutASummaryIsRefusedByName) {
  const std::string empty = testing::output_directory("no_run");
  testing::expect_mentions(testing::error_message([&] { read_outcome(empty); }), {empty + "/summary.json", "cannot be read"});
  std::ofstream(empty + "/summary.json") << "{\"status\": \"running\", \"counts\": ";
  testing::expect_mentions(testing::error_message([&] { read_outcome(empty); }), {"summary.json", "not JSON"});
  std::ofstream(empty + "/summary.json") << "{\"status\": \"finished\"}";
  testing::expect_mentions(testing::error_message([&] { read_outcome(empty); }), {"status", "finished", "expected"});
}

}  // namespace
}  // namespace kerf
