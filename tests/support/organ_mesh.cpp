#include "support/organ_mesh.h"

#include <gmsh.h>
#include <unistd.h>

#include "core/thread_scope.h"
#include "geometry/gmsh_module.h"
#include "support/msh_conversion.h"
#include "support/test_support.h"

namespace kerf::testing {

void write_organ_mesh(const std::string& path, double size_left, double size_right, int order) {
  SingleThreadScope serial;  // the same mesh every run
  gmsh_module().ensure_initialized();  // one gmsh in the process: the module's, set as kerf sets it
  gmsh::clear();
  gmsh::model::add("organ");
  const double a = 0.035, b = 0.025, c = 0.015, rest = -0.012;
  const int sphere = gmsh::model::occ::addSphere(0, 0, 0, 1.0);
  gmsh::model::occ::dilate({{3, sphere}}, 0, 0, 0, a, b, c);
  const int below = gmsh::model::occ::addBox(-1, -1, -1, 2, 2, 1.0 + rest);
  std::vector<std::pair<int, int>> kept;
  std::vector<std::vector<std::pair<int, int>>> map;
  gmsh::model::occ::cut({{3, sphere}}, {{3, below}}, kept, map);
  gmsh::model::occ::synchronize();
  // The size field alone: a box meshed before in this process leaves its size bounds set.
  gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
  gmsh::option::setNumber("Mesh.MeshSizeMax", 1e22);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.Algorithm3D", 1);
  const int grading = gmsh::model::mesh::field::add("MathEval");
  const double slope = (size_right - size_left) / (2 * a);
  gmsh::model::mesh::field::setString(
      grading, "F", std::to_string(size_left) + " + " + std::to_string(slope) + " * (x + " + std::to_string(a) + ")");
  gmsh::model::mesh::field::setAsBackgroundMesh(grading);
  gmsh::model::mesh::generate(3);
  if (order == 2) gmsh::model::mesh::setOrder(2);
  write_current_model(path, 4.1, false);
}

const std::string& graded_organ_file() {
  static const std::string path = [] {
    const std::string p = output_directory("GradedOrgan_" + std::to_string(::getpid())) + "/organ.msh";
    write_organ_mesh(p, 0.003, 0.006);
    return p;
  }();
  return path;
}

}  // namespace kerf::testing
