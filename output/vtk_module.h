#pragma once
// The VTK module (libkerf_vtk.so, core/module_loader.h): all kerf asks of
// VTK, loaded the first time a run writes a ParaView file.
#include <string>

#include "core/module_loader.h"
#include "output/vtk_series.h"

namespace kerf {

struct VtkModule {
  ModuleStamp stamp;
  void (*write_vtu)(const BodySnapshot& snapshot, const std::string& path);
  void (*write_vti)(const LatticeSnapshot& lattice, const std::string& path);
};

/// The module's table, loaded on the first call.
const VtkModule& vtk_module();

}  // namespace kerf
