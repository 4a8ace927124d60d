#pragma once
// gmsh is a process-wide singleton: initialise it once, quietly, and read the
// cells of one type out of the current model into a Mesh.
#include <string>

#include "geometry/mesh.h"

namespace kerf {

/// Initialises gmsh on first use (terminal output off, one thread).
void ensure_gmsh_initialized();


/// Fills `mesh` with the nodes and cells of the current gmsh model; `dimension`
/// picks tetrahedra (3) or triangles (2); throws if the model holds none.
void extract_gmsh_mesh(int dimension, const std::string& what, Mesh& mesh);

}  // namespace kerf
