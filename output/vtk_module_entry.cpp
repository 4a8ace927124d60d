// The VTK module's one exported symbol: its table (output/vtk_module.h).
#include "output/vtk_files.h"
#include "output/vtk_module.h"

KERF_MODULE_ENTRY const kerf::VtkModule* kerf_vtk_module() {
  static const kerf::VtkModule table{{kerf::version, sizeof(kerf::VtkModule)}, kerf::vtk_write_vtu,
                                     kerf::vtk_write_vti};
  return &table;
}
