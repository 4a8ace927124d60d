// The gmsh module's one exported symbol: its table (geometry/gmsh_module.h).
#include "geometry/gmsh_meshing.h"
#include "geometry/gmsh_module.h"
#include "geometry/gmsh_session.h"

KERF_MODULE_ENTRY const kerf::GmshModule* kerf_gmsh_module() {
  static const kerf::GmshModule table{{kerf::version, sizeof(kerf::GmshModule)}, kerf::gmsh_mesh_box,
                                      kerf::gmsh_read_msh, kerf::gmsh_mesh_geo_file, kerf::ensure_gmsh_initialized};
  return &table;
}
