#include "support/msh_conversion.h"

#include <gmsh.h>

#include "core/thread_scope.h"
#include "geometry/gmsh_module.h"

namespace kerf::testing {

void write_current_model(const std::string& path, double version, bool binary) {
  gmsh::option::setNumber("Mesh.MshFileVersion", version);
  gmsh::option::setNumber("Mesh.Binary", binary ? 1 : 0);
  gmsh::write(path);
  gmsh::option::setNumber("Mesh.Binary", 0);
  gmsh::clear();
}

void write_msh_as(const std::string& from, const std::string& to, double version, bool binary) {
  SingleThreadScope serial;
  gmsh_module().ensure_initialized();  // one gmsh in the process: the module's, set as kerf sets it
  gmsh::clear();
  gmsh::open(from);
  write_current_model(to, version, binary);
}

void write_plate_with_hole(const std::string& path, double size, int order) {
  SingleThreadScope serial;
  gmsh_module().ensure_initialized();
  gmsh::clear();
  gmsh::model::add("plate");
  const int plate = gmsh::model::occ::addRectangle(0, 0, 0, 0.1, 0.05);
  const int hole = gmsh::model::occ::addDisk(0.05, 0.025, 0, 0.01, 0.01);
  std::vector<std::pair<int, int>> kept;
  std::vector<std::vector<std::pair<int, int>>> map;
  gmsh::model::occ::cut({{2, plate}}, {{2, hole}}, kept, map);
  gmsh::model::occ::synchronize();
  gmsh::option::setNumber("Mesh.MeshSizeMin", size);
  gmsh::option::setNumber("Mesh.MeshSizeMax", size);
  gmsh::model::mesh::generate(2);
  if (order == 2) gmsh::model::mesh::setOrder(2);
  write_current_model(path, 4.1, false);
}

void write_two_boxes(const std::string& path) {
  SingleThreadScope serial;
  gmsh_module().ensure_initialized();
  gmsh::clear();
  gmsh::model::add("two_boxes");
  gmsh::model::occ::addBox(0, 0, 0, 1, 0.5, 0.5, 1);
  gmsh::model::occ::addBox(1, 0, 0, 1, 0.5, 0.5, 2);
  std::vector<std::pair<int, int>> kept;
  std::vector<std::vector<std::pair<int, int>>> map;
  gmsh::model::occ::fragment({{3, 1}}, {{3, 2}}, kept, map);
  gmsh::model::occ::synchronize();
  gmsh::option::setNumber("Mesh.MeshSizeMin", 0.3);
  gmsh::option::setNumber("Mesh.MeshSizeMax", 0.3);
  gmsh::model::mesh::generate(3);
  write_current_model(path, 2.2, false);
}

}  // namespace kerf::testing
