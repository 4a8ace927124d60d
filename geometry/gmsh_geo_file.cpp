#include <gmsh.h>

#include "core/thread_scope.h"
#include "geometry/gmsh_meshing.h"
#include "geometry/gmsh_session.h"

namespace kerf {

void gmsh_mesh_geo_file(const std::string& geo, double size, int order, const std::string& msh) {
  SingleThreadScope serial;  // the same mesh every run
  ensure_gmsh_initialized();
  gmsh::clear();
  gmsh::open(geo);
  gmsh::option::setNumber("Mesh.MeshSizeMin", size);
  gmsh::option::setNumber("Mesh.MeshSizeMax", size);
  gmsh::model::mesh::generate(3);
  if (order == 2) gmsh::model::mesh::setOrder(2);
  gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
  gmsh::option::setNumber("Mesh.Binary", 0);
  gmsh::write(msh);
  gmsh::clear();
}

}  // namespace kerf
