#include "output/vtk_module.h"

namespace kerf {

const VtkModule& vtk_module() {
  static const VtkModule& table = load_module<VtkModule>("vtk", "to write ParaView's files (output.vtk)");
  return table;
}

void write_vtu(const BodySnapshot& snapshot, const std::string& path) { vtk_module().write_vtu(snapshot, path); }

void write_vti(const LatticeSnapshot& lattice, const std::string& path) { vtk_module().write_vti(lattice, path); }

}  // namespace kerf
