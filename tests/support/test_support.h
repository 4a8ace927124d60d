#pragma once
// Helpers shared by the tests: scenes from text, small meshes, full stiffness matrices.
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "discretization/fem/fem_body.h"
#include "problem/scene.h"
#include "solvers/sparse_assembly.h"

namespace kerf::testing {

/// Parses a scene given as YAML text (relative paths from the source tree's scenes/).
Scene scene_from_text(const std::string& yaml, const std::vector<std::string>& overrides = {});
/// The message reading the scene throws (kerf::Error), or "" when it reads.
std::string scene_refusal(const std::string& yaml, const std::vector<std::string>& overrides = {});
/// EXPECTs that `text` holds `part`, printing both otherwise.
void expect_contains(const std::string& text, const std::string& part);

/// A fresh output directory `name` under the build tree, inside a folder of
/// the running test's own (test_output/Suite.Test/name): tests that ctest
/// runs at once never share one, whatever names they pick.
std::string output_directory(const std::string& name);
/// The path output_directory(name) gives, left as it is (to read a run's files).
std::string output_path(const std::string& name);

/// A mesh of the unit box [0,1]^dim made by gmsh.
Mesh unit_box_mesh(int dimension, int order, double size);

/// K(u) over all dofs, assembled through the body's sink.
SparseMatrix assemble_stiffness(const DiscreteBody& body, const Vector& u);

std::string source_path(const std::string& relative);

/// The message of the kerf::Error that `action` throws; fails the test (and
/// returns "") when it throws none.
std::string error_message(const std::function<void()>& action);
/// Expects `message` to hold every one of `parts` (what the user must be told).
void expect_mentions(const std::string& message, std::initializer_list<std::string> parts);

/// Runs a scene file of the source tree quietly with `overrides`, output under
/// the test's own directory; returns summary.json.
nlohmann::ordered_json run_scene_file(const std::string& scene_file, std::vector<std::string> overrides,
                                      const std::string& test_name);

/// The same without ParaView output, expecting the run to end well (the
/// failure names the test and the run's error); returns summary.json.
nlohmann::ordered_json run_scene_file_ok(const std::string& scene_file, std::vector<std::string> overrides,
                                         const std::string& test_name);

/// Runs a scene given as YAML text quietly, its output where `overrides` put
/// it (output.dir); returns summary.json, also when the run stopped with an
/// error (then "status" is "error" and "error" the message).
nlohmann::ordered_json run_scene_text(const std::string& yaml, const std::vector<std::string>& overrides);

}  // namespace kerf::testing
