#pragma once
// kerf's own reader of gmsh's .msh files (MSH 4.1 and 2.2, ASCII or binary):
// the mesh gmsh's reader gives (the same nodes in the same order, the same
// cells), without loading gmsh. read_msh (geometry/msh_reader.h) tries it
// first and hands gmsh the files it leaves.
#include <optional>
#include <string>

#include "geometry/msh_reader.h"

namespace kerf {

/// The mesh, or nullopt for a file left to gmsh (geometry/msh_content.h
/// says which). A malformed file throws kerf::Error naming its line.
std::optional<Mesh> read_msh_without_gmsh(const std::string& path, int dimension, MshOrder order,
                                          int* file_order = nullptr);

}  // namespace kerf
