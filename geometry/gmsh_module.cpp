#include "geometry/gmsh_module.h"

namespace kerf {

const GmshModule& gmsh_module() {
  static const GmshModule& table = load_module<GmshModule>("gmsh", "to mesh with gmsh or read a .msh file");
  return table;
}

Mesh mesh_box(const BoxMeshRequest& request) { return gmsh_module().mesh_box(request); }

}  // namespace kerf
