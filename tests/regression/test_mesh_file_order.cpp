// A mesh file's cell order against the element the scene asks: never run
// silently another. The organ (tests/support/organ_mesh.h) written twice from
// one gmsh mesh, linear and with curved mid-edge nodes, sags under its weight
// on its flat base; each element is asked of each file.
#include <gtest/gtest.h>

#include <unistd.h>

#include "support/organ_mesh.h"
#include "support/test_support.h"

namespace kerf {
namespace {

using json = nlohmann::ordered_json;

/// The organ's two files, written once per process.
const std::string& organ_file(int order) {
  static const std::string folder = testing::output_directory("MeshFileOrder_" + std::to_string(::getpid()));
  static const std::string linear = [] {
    testing::write_organ_mesh(folder + "/linear.msh", 0.005, 0.008, 1);
    return folder + "/linear.msh";
  }();
  static const std::string quadratic = [] {
    testing::write_organ_mesh(folder + "/quadratic.msh", 0.005, 0.008, 2);
    return folder + "/quadratic.msh";
  }();
  return order == 1 ? linear : quadratic;
}

json sag(int file_order, const std::string& element) {
  const std::string name = "order" + std::to_string(file_order) + "_" + element;
  return testing::run_scene_text(
      "domain: {mesh: " + organ_file(file_order) + "}\n"
      "material: {young: 3000, poisson: 0.45, density: 1000}\n"
      "body_force: {gravity: [0, 0, -9.81]}\n"
      "discretization: {method: fem, fem: {element: " + element + "}}\n"
      "boundary:\n  - {select: {plane: {axis: z, at: -0.012}}, fix: [x, y, z]}\n"
      "solve: {analysis: static}\n"
      "output:\n  probes:\n    - {name: top, point: [0.0, 0.0, 0.0149], field: displacement}\n",
      {"output.dir=" + testing::output_directory("MeshFileOrder_" + name), "output.vtk=false"});
}

double top_sag(const json& s) { return -s["probes"]["top"]["displacement"][2].get<double>(); }

std::string notes(const json& s) {
  std::string all;
  for (const auto& note : s["notes"]) all += note.get<std::string>() + "\n";
  return all;
}

// tet10 on the linear file: gmsh raises it, the run says so, and its answer is
// the quadratic file's (which differs only by the mid-edge nodes of the
// curved surface), not tet4's.
TEST(MeshFileOrder, Tet10OnALinearFileIsRaisedToSecondOrderAndSaysSo) {
  const json raised = sag(1, "tet10"), curved = sag(2, "tet10"), linear = sag(1, "tet4");
  ASSERT_EQ(raised["status"], "ok") << raised.dump();
  ASSERT_EQ(curved["status"], "ok") << curved.dump();
  ASSERT_EQ(linear["status"], "ok") << linear.dump();
  testing::expect_mentions(notes(raised), {"discretization.fem.element: tet10", organ_file(1), "linear",
                                           "raised them to second order"});
  EXPECT_TRUE(curved["notes"].empty()) << notes(curved);
  EXPECT_EQ(raised["counts"]["nodes"], curved["counts"]["nodes"]);
  std::printf("organ sag: tet4 %.6e, tet10 raised %.6e, tet10 curved %.6e m\n", top_sag(linear), top_sag(raised),
              top_sag(curved));
  EXPECT_NEAR(top_sag(raised), top_sag(curved), 0.01 * top_sag(curved));
  // tet4 locks at nu 0.45: tet10 sags clearly more.
  EXPECT_GT(top_sag(raised), 1.05 * top_sag(linear));
}

// tet4 on the quadratic file takes its corners, which are the linear file's
// nodes: the linear file's answer to round-off, and the run says so.
TEST(MeshFileOrder, Tet4OnAQuadraticFileTakesItsCornersAndSaysSo) {
  const json corners = sag(2, "tet4"), linear = sag(1, "tet4");
  ASSERT_EQ(corners["status"], "ok") << corners.dump();
  testing::expect_mentions(notes(corners), {"discretization.fem.element: tet4", organ_file(2), "quadratic",
                                            "corner nodes"});
  EXPECT_TRUE(linear["notes"].empty()) << notes(linear);
  EXPECT_EQ(corners["counts"]["nodes"], linear["counts"]["nodes"]);
  EXPECT_NEAR(top_sag(corners), top_sag(linear), 1e-10 * top_sag(linear));
}

}  // namespace
}  // namespace kerf
