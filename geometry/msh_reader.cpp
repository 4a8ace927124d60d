#include "geometry/msh_reader.h"

#include "geometry/gmsh_module.h"
#include "geometry/native_msh_reader.h"

namespace kerf {

Mesh read_msh(const std::string& path, int dimension, MshOrder order, int* file_order) {
  if (std::optional<Mesh> mesh = read_msh_without_gmsh(path, dimension, order, file_order)) return std::move(*mesh);
  return gmsh_module().read_msh(path, dimension, order, file_order);
}

}  // namespace kerf
