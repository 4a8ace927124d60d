#pragma once
// gmsh is a process-wide singleton: initialise it once, quietly, and read the
// cells of one type out of the current model into a Mesh.
#include <string>

#include "geometry/mesh.h"

namespace kerf {

/// Initialises gmsh on first use (terminal output off, one thread).
void ensure_gmsh_initialized();

/// gmsh's meshers are not deterministic on several threads (node positions and
/// cells change from run to run), and gmsh sets the process-wide OpenMP thread
/// count: inside this scope gmsh runs on one thread, and kerf's count is back
/// afterwards.
class SerialGmshScope {
 public:
  SerialGmshScope();
  ~SerialGmshScope();
  SerialGmshScope(const SerialGmshScope&) = delete;
  SerialGmshScope& operator=(const SerialGmshScope&) = delete;

 private:
  int threads_;
};

/// Fills `mesh` with the nodes and cells of the current gmsh model; `dimension`
/// picks tetrahedra (3) or triangles (2); throws if the model holds none.
void extract_gmsh_mesh(int dimension, const std::string& what, Mesh& mesh);

}  // namespace kerf
