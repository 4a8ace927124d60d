#include "support/test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "app/run_scene.h"
#include "core/check.h"
#include "geometry/box_mesher.h"
#include "problem/scene_reader.h"

namespace kerf::testing {

Scene scene_from_text(const std::string& yaml, const std::vector<std::string>& overrides) {
  return parse_scene(yaml, "test.yaml", source_path("scenes"), overrides);
}

std::string scene_refusal(const std::string& yaml, const std::vector<std::string>& overrides) {
  try {
    scene_from_text(yaml, overrides);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

void expect_contains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in: " << text;
}

std::string output_path(const std::string& name) {
  const ::testing::UnitTest& tests = *::testing::UnitTest::GetInstance();
  std::string owner = "outside_a_test";
  if (const ::testing::TestInfo* test = tests.current_test_info())
    owner = std::string(test->test_suite_name()) + "." + test->name();
  else if (const ::testing::TestSuite* suite = tests.current_test_suite())
    owner = suite->name();  // SetUpTestSuite: shared by the suite's tests, run in one process
  std::replace(owner.begin(), owner.end(), '/', '_');  // parametrized names hold '/'
  return std::string(KERF_BINARY_DIR) + "/test_output/" + owner + "/" + name;
}

std::string output_directory(const std::string& name) {
  const std::string dir = output_path(name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

Mesh unit_box_mesh(int dimension, int order, double size) {
  BoxMeshRequest r;
  r.dimension = dimension;
  r.order = order;
  r.min = Vec3::Zero();
  r.max = dimension == 3 ? Vec3::Ones() : Vec3(1, 1, 0);
  r.size = size;
  return mesh_box(r);
}

SparseMatrix assemble_stiffness(const DiscreteBody& body, const Vector& u) {
  SparseMatrix K = build_pattern(body);
  body.tangent(u, add_into(K), nullptr);
  return K;
}

std::string source_path(const std::string& relative) { return std::string(KERF_SOURCE_DIR) + "/" + relative; }

std::string error_message(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a kerf::Error, none was thrown";
  return "";
}

void expect_mentions(const std::string& message, std::initializer_list<std::string> parts) {
  for (const std::string& part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' is not in the message: " << message;
}

nlohmann::ordered_json run_scene_file(const std::string& scene_file, std::vector<std::string> overrides,
                                      const std::string& test_name) {
  overrides.push_back("output.dir=" + output_directory(test_name));
  Scene scene = read_scene(source_path(scene_file), overrides);
  RunOptions options;
  options.quiet = true;
  return run_scene(scene, options).summary;
}

nlohmann::ordered_json run_scene_file_ok(const std::string& scene_file, std::vector<std::string> overrides,
                                         const std::string& test_name) {
  overrides.push_back("output.vtk=false");
  nlohmann::ordered_json s = run_scene_file(scene_file, std::move(overrides), test_name);
  EXPECT_EQ(s["status"], "ok") << test_name << ": " << s.value("error", "");
  return s;
}

nlohmann::ordered_json run_scene_text(const std::string& yaml, const std::vector<std::string>& overrides) {
  const Scene scene = scene_from_text(yaml, overrides);
  RunOptions options;
  options.quiet = true;
  try {
    return run_scene(scene, options).summary;
  } catch (const Error&) {
    std::ifstream in(scene.output.dir + "/summary.json");
    return nlohmann::ordered_json::parse(in);
  }
}

}  // namespace kerf::testing
