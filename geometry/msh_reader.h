#pragma once
// Reads a gmsh .msh file (tetrahedra in 3D, triangles in 2D). gmsh 4.8's own
// reader can crash on malformed files, so it runs in a child process: a bad
// file ends in a kerf::Error naming the file, never in a crash of kerf.
#include <string>

#include "geometry/mesh.h"

namespace kerf {

Mesh read_msh(const std::string& path, int dimension);

}  // namespace kerf
