#pragma once
// Inside the gmsh module only (geometry/gmsh_module.h is the door): the
// functions its table gives, which call gmsh.
#include <string>

#include "geometry/box_mesher.h"
#include "geometry/msh_reader.h"

namespace kerf {

Mesh gmsh_mesh_box(const BoxMeshRequest& request);
Mesh gmsh_read_msh(const std::string& path, int dimension, MshOrder order, int* file_order);
void gmsh_mesh_geo_file(const std::string& geo, double size, int order, const std::string& msh);

}  // namespace kerf
