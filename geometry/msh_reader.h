#pragma once
// Reads a gmsh .msh file (tetrahedra in 3D, triangles in 2D). gmsh 4.8's own
// reader can crash on malformed files, so it runs in a child process: a bad
// file ends in a kerf::Error naming the file, never in a crash of kerf.
#include <string>

#include "geometry/mesh.h"

namespace kerf {

/// The cells' order: the file's, or second order (gmsh adds the mid-edge
/// nodes of a linear file, on its straight edges; a quadratic file is kept).
enum class MshOrder { as_in_file, second };

/// `file_order`, when given, receives the order the file itself holds.
Mesh read_msh(const std::string& path, int dimension, MshOrder order = MshOrder::as_in_file,
              int* file_order = nullptr);

}  // namespace kerf
