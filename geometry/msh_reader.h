#pragma once
// Reads a gmsh .msh file (tetrahedra in 3D, triangles in 2D). kerf reads MSH
// 4.1 and 2.2 itself (geometry/native_msh_reader.h), without loading gmsh;
// other files go to gmsh's reader, in a child process, since gmsh 4.8 can
// crash on malformed files: a bad file ends in a kerf::Error naming the file
// (and, read by kerf, the line), never in a crash of kerf.
#include <string>

#include "geometry/mesh.h"

namespace kerf {

/// The cells' order: the file's, or second order (mid-edge nodes added to
/// a linear file on its straight edges, as gmsh adds them; a quadratic file is kept).
enum class MshOrder { as_in_file, second };

/// `file_order`, when given, receives the order the file itself holds.
Mesh read_msh(const std::string& path, int dimension, MshOrder order = MshOrder::as_in_file,
              int* file_order = nullptr);

}  // namespace kerf
