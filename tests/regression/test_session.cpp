// A session stepped by its caller (app/session.h): what `kerf run` does is a
// loop over one, so a session read between its steps must give that run's
// answer to the last digit, and one ended early must leave readable results
// where it stopped.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

#include "app/session.h"
#include "core/check.h"
#include "problem/scene_reader.h"
#include "support/test_support.h"

namespace kerf {
namespace {

using json = nlohmann::ordered_json;

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

Scene quiet_scene(const std::string& file, std::vector<std::string> overrides, const std::string& directory) {
  overrides.push_back("output.dir=" + testing::output_directory(directory));
  return read_scene(testing::source_path(file), overrides);
}

RunOptions quiet() {
  RunOptions options;
  options.quiet = true;
  return options;
}

struct GrowingCutCase {
  const char* name;
  const char* scene;
  std::vector<std::string> overrides;
};

// A cut growing through the body as it moves: nodal integration and EFG
// update their shape functions in place, FEM splits its cells anew.
const std::vector<GrowingCutCase> growing_cut_cases = {
    {"nodal", "scenes/cutting_2d.yaml", {"solve.duration=6e-4"}},
    {"efg", "scenes/cutting_2d.yaml",
     {"discretization.method=efg", "solve.dt=1e-5", "solve.duration=6e-4",
      "discretization.meshless.nitsche_safety=8"}},
    {"nodal_organ", "scenes/organ_cut.yaml", {"solve.duration=0.16", "output.vtk={every: 1000}"}},  // through a node
    {"fem_split", "scenes/organ_cut.yaml",
     {"discretization.method=fem", "cuts.0.fem=split", "solve.duration=0.11", "output.vtk={every: 40}"}},
};

TEST(Session, ReadBetweenItsStepsGivesTheBatchRunsAnswerToTheLastDigit) {
  for (const GrowingCutCase& c : growing_cut_cases) {
    const std::string batch_dir = std::string(c.name) + "_batch", session_dir = std::string(c.name) + "_session";
    const json batch = run_scene(quiet_scene(c.scene, c.overrides, batch_dir), quiet()).summary;
    Session session(quiet_scene(c.scene, c.overrides, session_dir), quiet());
    double last_time = session.time();
    while (!session.done()) {
      session.step();
      EXPECT_GT(session.time(), last_time) << c.name;
      last_time = session.time();
      const Vector& u = session.displacement();
      ASSERT_EQ(u.size(), session.node_count() * session.dofs_per_node()) << c.name;
      EXPECT_TRUE(u.allFinite()) << c.name;
      EXPECT_EQ(session.velocity().size(), u.size()) << c.name;
      (void)session.probes();
    }
    const json stepped = session.finish().summary;
    EXPECT_EQ(stepped["probes"].dump(), batch["probes"].dump()) << c.name;
    EXPECT_EQ(stepped["counts"].dump(), batch["counts"].dump()) << c.name;
    EXPECT_GT(stepped["timing"]["cut_update_ms"]["count"].get<int>(), 0) << c.name;  // the cut grew
    EXPECT_EQ(file_text(testing::output_path(session_dir) + "/probes.csv"),
              file_text(testing::output_path(batch_dir) + "/probes.csv"))
        << c.name;
  }
}

/// Steps `live` to its end, feeding cut 0 the vertices of `whole` (the same
/// cut given with its times) that `live` lacks, each within the step its time
/// falls in: after the session reached t, before the step that ends past it.
json feed_the_cut_live(const Scene& whole, Scene live) {
  const Cut& cut = whole.cuts.at(0);
  std::size_t fed = 0;
  while (fed < cut.vertices.size() && cut.times[fed] <= 0.0) ++fed;
  live.cuts.at(0).vertices.assign(cut.vertices.begin(), cut.vertices.begin() + fed);
  live.cuts.at(0).times.assign(cut.times.begin(), cut.times.begin() + fed);
  live.cuts.at(0).live = true;
  Session session(live, quiet());
  while (!session.done()) {
    std::vector<Vec3> next;
    for (; fed < cut.vertices.size() && cut.times[fed] <= session.time() + session.time_step(); ++fed)
      next.push_back(cut.vertices[fed]);
    if (!next.empty()) session.extend_cut(0, next);
    session.step();
  }
  return session.finish().summary;
}

// The scene's cut fed vertex by vertex as the run goes, the way a blade moved
// by a person gives it: the run the scene gives whole, to the last digit.
TEST(Session, ACutFedAsTheRunGoesGivesTheBatchRunsAnswerToTheLastDigit) {
  for (const GrowingCutCase& c : growing_cut_cases) {
    const std::string batch_dir = std::string(c.name) + "_batch", live_dir = std::string(c.name) + "_live";
    const Scene whole = quiet_scene(c.scene, c.overrides, batch_dir);
    const json batch = run_scene(whole, quiet()).summary;
    const json live = feed_the_cut_live(whole, quiet_scene(c.scene, c.overrides, live_dir));
    EXPECT_EQ(live["probes"].dump(), batch["probes"].dump()) << c.name;
    EXPECT_EQ(live["timing"]["cut_update_ms"]["count"], batch["timing"]["cut_update_ms"]["count"]) << c.name;
    EXPECT_EQ(file_text(testing::output_path(live_dir) + "/probes.csv"),
              file_text(testing::output_path(batch_dir) + "/probes.csv"))
        << c.name;
  }
}

TEST(Session, RefusesAPieceThatFoldsTheCutOrMissesTheBodyAndKeepsTheCutAsItWas) {
  Scene scene = quiet_scene("scenes/organ_cut.yaml", {"solve.duration=0.01", "cuts.0.strip=[]", "cuts.0.times=[]"},
                            "fold");
  Session session(scene, quiet());
  const std::vector<Vec3> blade{{-0.045, 0, 0.02}, {-0.045, 0, -0.004}, {-0.03, 0, 0.02}, {-0.03, 0, -0.004}};
  session.extend_cut(0, blade);
  session.step();
  // The blade turned back on itself: the next triangle faces the other way.
  const std::vector<Vec3> folded{{-0.045, 0.0, 0.02}, {-0.045, 0.0, -0.004}};
  testing::expect_mentions(testing::error_message([&] { session.extend_cut(0, folded); }),
                           {"cuts.0", "fed at run time", "folds"});
  testing::expect_mentions(testing::error_message([&] { session.extend_cut(1, blade); }), {"cut 1", "1 cut"});
  Session scripted(quiet_scene("scenes/organ_cut.yaml", {"solve.duration=0.01"}, "scripted"), quiet());
  testing::expect_mentions(testing::error_message([&] { scripted.extend_cut(0, blade); }),
                           {"cuts.0.live", "not declared live", "live: true"});
  const std::vector<Vec3> onward{{-0.015, 0, 0.02}, {-0.015, 0, -0.004}};
  session.extend_cut(0, onward);  // the cut as it was takes the next pair
  while (!session.done()) session.step();
  EXPECT_EQ(session.finish().summary["status"], "ok");
  // A blade held off the organ (a hand overshooting): its pieces would cut nothing.
  Session off_body(scene, quiet());
  const std::vector<Vec3> above{{0.3, 0.2, 0.25}, {0.3, 0.2, 0.22}}, further{{0.32, 0.2, 0.25}, {0.32, 0.2, 0.22}};
  off_body.extend_cut(0, above);  // where the blade starts: no piece yet
  testing::expect_mentions(testing::error_message([&] { off_body.extend_cut(0, further); }),
                           {"cuts.0", "outside the body", "[0.32  0.2 0.25]", "kept as it was"});
  const std::vector<Vec3> into{{-0.03, 0, 0.02}, {-0.03, 0, -0.004}};
  off_body.extend_cut(0, into);  // from there into the organ: kept
  off_body.step();
  EXPECT_EQ(off_body.finish().summary["status"], "ok");
}

TEST(Session, EndedEarlyLeavesItsResultsWhereItStopped) {
  Session session(quiet_scene("scenes/organ_cut.yaml", {"solve.duration=0.1", "output.vtk={every: 1000}"}, "early"),
                  quiet());
  for (int i = 0; i < 7; ++i) session.step();
  const double stopped_at = session.time();
  const json summary = session.finish().summary;
  EXPECT_EQ(summary["status"], "ok");
  const json written = json::parse(file_text(testing::output_path("early") + "/summary.json"));
  EXPECT_EQ(written["status"], "ok");
  // probes.csv's last row is the state the session stopped at, and the ParaView series ends there too.
  std::istringstream rows(file_text(testing::output_path("early") + "/probes.csv"));
  std::string row, last;
  while (std::getline(rows, row))
    if (!row.empty()) last = row;
  EXPECT_NEAR(std::stod(last.substr(0, last.find(','))), stopped_at, 1e-12);
  testing::expect_contains(file_text(testing::output_path("early") + "/organ_cut.pvd"), "organ_cut_0001.vtu");
}

TEST(Session, RefusesAStepPastItsEndNamingWhatSetsIt) {
  Session session(quiet_scene("scenes/plate_tension_2d.yaml", {"solve.load_steps=2"}, "past_end"), quiet());
  session.step();
  session.step();
  EXPECT_TRUE(session.done());
  testing::expect_mentions(testing::error_message([&] { session.step(); }),
                           {"every step", "solve.load_steps", "finish"});
  EXPECT_EQ(session.finish().summary["status"], "ok");
  testing::expect_mentions(testing::error_message([&] { session.finish(); }), {"finished already"});
}

TEST(Session, GivesTheContactForceItsProbeGives) {
  Session session(quiet_scene("scenes/indentation.yaml", {"solve.duration=0.01"}, "contact_force"), quiet());
  for (int i = 0; i < 12; ++i) session.step();
  const Vec3 force = session.contact_force(0);
  const json probe = session.probes()["push"]["contact_force"];
  EXPECT_LT(force.z(), 0.0);  // pressing by now
  for (int k = 0; k < 3; ++k) EXPECT_EQ(force[k], probe[k].get<double>()) << k;
  testing::expect_mentions(testing::error_message([&] { session.contact_force(1); }),
                           {"sphere 1", "'contact'", "1 spheres"});
}

}  // namespace
}  // namespace kerf

namespace kerf {
namespace {

/// The probes of `scene` run by a session whose hand sets sphere 0 before the first step (`hand`), then steps to the end.
json probes_with_a_hand(const Scene& scene, const std::function<void(Session&)>& hand) {
  Session session(scene, quiet());
  hand(session);
  while (!session.done()) session.step();
  return session.finish().summary["probes"];
}

// A sphere moved by a session where its scene would have put it: the same
// run to the last digit (a haptic device's tool moved between steps).
TEST(Session, ASphereMovedByTheSessionGivesTheRunItsSceneWouldGive) {
  auto scene = [&](const std::string& displacement, const std::string& dir) {
    return quiet_scene("scenes/indentation.yaml", {"solve.duration=0.02", "output.vtk=false", "contact.0.force=null",
                                                   "contact.0.displacement=" + displacement}, dir);
  };
  const json batch = run_scene(scene("[0, 0, -0.002]", "move_batch"), quiet()).summary["probes"];
  const json live = probes_with_a_hand(scene("[0, 0, -0.004]", "move_live"),
                                       [](Session& s) { s.move_sphere(0, Vec3(0, 0, -0.002)); });
  EXPECT_EQ(live.dump(), batch.dump());
  EXPECT_LT(live["push"]["contact_force"][2].get<double>(), 0.0);  // it presses
}

// A sphere pushed by a session with half its scene's force settles where the
// body pushes back as hard, as deep as Hertz says (depth ~ F^(2/3)).
TEST(Session, ASpherePushedByTheSessionSettlesUnderThatForce) {
  const json full = run_scene(quiet_scene("scenes/indentation.yaml", {"output.vtk=false"}, "push_full"), quiet())
                        .summary["probes"];
  const json half = probes_with_a_hand(quiet_scene("scenes/indentation.yaml", {"output.vtk=false"}, "push_half"),
                                       [](Session& s) { s.push_sphere(0, Vec3(0, 0, -0.005)); });
  EXPECT_NEAR(half["push"]["contact_force"][2].get<double>(), -0.005, 0.03 * 0.005);
  const double ratio = half["indent"]["indentation"].get<double>() / full["indent"]["indentation"].get<double>();
  EXPECT_NEAR(ratio, std::pow(0.5, 2.0 / 3.0), 0.05) << ratio;
}

// Loads halved by the session before the first step: the run with half the
// scene's gravity, to the last digit; let go midway, the body sags less than
// the one that kept its weight.
TEST(Session, LoadsScaledByTheSessionGiveTheRunWithThoseLoads) {
  const std::vector<std::string> short_run{"solve.duration=0.05", "output.vtk=false",
                                           "output.probes=[{name: low, point: [0.03, 0.01, 0.0], field: displacement}]"};
  auto scene = [&](const std::string& gravity, const std::string& dir) {
    std::vector<std::string> more = short_run;
    more.push_back("body_force.gravity=" + gravity);
    return quiet_scene("tests/viewer/hanging_block.yaml", more, dir);
  };
  const json batch = run_scene(scene("[0, 0, -4.905]", "loads_batch"), quiet()).summary["probes"];
  const json live = probes_with_a_hand(scene("[0, 0, -9.81]", "loads_live"), [](Session& s) { s.scale_loads(0.5); });
  EXPECT_EQ(live.dump(), batch.dump());
  const json kept = run_scene(scene("[0, 0, -9.81]", "loads_kept"), quiet()).summary["probes"];
  const json let_go = probes_with_a_hand(scene("[0, 0, -9.81]", "loads_let_go"), [](Session& s) {
    for (int i = 0; i < 20; ++i) s.step();
    s.scale_loads(0.0);
  });
  const double z_kept = kept["low"]["displacement"][2].get<double>(), z_let_go = let_go["low"]["displacement"][2];
  EXPECT_LT(z_kept, 0.0);
  EXPECT_GT(z_let_go, 0.75 * z_kept) << z_let_go << " against " << z_kept;  // measured: 0.51 of it
  Session still(quiet_scene("scenes/plate_tension_2d.yaml", {}, "loads_static"), quiet());
  testing::expect_mentions(testing::error_message([&] { still.scale_loads(2.0); }), {"solve.analysis", "dynamic"});
}

TEST(Session, RefusesAHandThatTakesASphereOffTheSurfaceSampledForIt) {
  Session pushed(quiet_scene("scenes/indentation.yaml", {"solve.duration=0.002"}, "hand_push"), quiet());
  testing::expect_mentions(testing::error_message([&] { pushed.push_sphere(0, Vec3(0, 0, -0.02)); }),
                           {"indentation.yaml", "key 'force'", "no larger"});
  testing::expect_mentions(testing::error_message([&] { pushed.push_sphere(0, Vec3(0.001, 0, -0.005)); }),
                           {"key 'force'", "along that line"});
  testing::expect_mentions(testing::error_message([&] { pushed.move_sphere(0, Vec3(0, 0, -0.001)); }),
                           {"key 'force'", "driven by a force"});
  testing::expect_mentions(testing::error_message([&] { pushed.push_sphere(1, Vec3(0, 0, -0.001)); }),
                           {"sphere 1", "'contact'"});
  Session moved(quiet_scene("scenes/indentation.yaml",
                            {"solve.duration=0.002", "contact.0.force=null", "contact.0.displacement=[0, 0, -0.002]"},
                            "hand_move"),
                quiet());
  moved.move_sphere(0, Vec3(0.001, 0, -0.003));  // within twice the path of it
  testing::expect_mentions(testing::error_message([&] { moved.move_sphere(0, Vec3(0.01, 0, -0.002)); }),
                           {"key 'displacement'", "scene path", "sampled"});
  moved.step();
  EXPECT_EQ(moved.finish().summary["status"], "ok");
  Session still(quiet_scene("scenes/indentation.yaml", {"solve.analysis=static"}, "hand_static"), quiet());
  testing::expect_mentions(testing::error_message([&] { still.push_sphere(0, Vec3(0, 0, -0.005)); }),
                           {"solve.analysis", "dynamic"});
}

}  // namespace
}  // namespace kerf
