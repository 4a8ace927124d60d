#pragma once
// The gmsh module (libkerf_gmsh.so, core/module_loader.h): all kerf asks of
// gmsh, loaded the first time a run meshes a box or reads a .msh file.
#include <string>

#include "core/module_loader.h"
#include "geometry/box_mesher.h"
#include "geometry/msh_reader.h"

namespace kerf {

struct GmshModule {
  ModuleStamp stamp;
  Mesh (*mesh_box)(const BoxMeshRequest& request);
  Mesh (*read_msh)(const std::string& path, int dimension, MshOrder order, int* file_order);
  /// A .geo file meshed at `size` (m) and `order`, written as a .msh file.
  void (*mesh_geo_file)(const std::string& geo, double size, int order, const std::string& msh);
  /// gmsh initialized as kerf sets it (one thread, quiet), for a caller using gmsh's API beside kerf.
  void (*ensure_initialized)();
};

/// The module's table, loaded on the first call.
const GmshModule& gmsh_module();

}  // namespace kerf
