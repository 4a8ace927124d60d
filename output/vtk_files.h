#pragma once
// Inside the VTK module only (output/vtk_module.h is the door): the files it writes with VTK.
#include <string>

#include "output/vtk_series.h"

namespace kerf {

void vtk_write_vtu(const BodySnapshot& snapshot, const std::string& path);
void vtk_write_vti(const LatticeSnapshot& lattice, const std::string& path);

}  // namespace kerf
