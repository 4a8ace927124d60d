#include "geometry/gmsh_session.h"

#include <gmsh.h>

#include <algorithm>
#include <unordered_map>

#include "core/check.h"
#include "core/thread_scope.h"
#include "geometry/mesh_from_cells.h"

namespace kerf {

void ensure_gmsh_initialized() {
  static bool initialized = false;
  if (initialized) return;
  SingleThreadScope serial;  // gmsh sets the OpenMP thread count itself
  gmsh::initialize();
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.Verbosity", 1);
  gmsh::option::setNumber("General.NumThreads", 1);
  initialized = true;
}

void extract_gmsh_mesh(int dimension, const std::string& what, Mesh& mesh) {
  std::vector<int> volume_types, types;
  if (dimension == 2) gmsh::model::mesh::getElementTypes(volume_types, 3);
  gmsh::model::mesh::getElementTypes(types, dimension);
  const int linear_type = element_descriptor(dimension, 1).gmsh_type;
  const int quadratic_type = element_descriptor(dimension, 2).gmsh_type;
  const bool has_linear = std::find(types.begin(), types.end(), linear_type) != types.end();
  const bool has_quadratic = std::find(types.begin(), types.end(), quadratic_type) != types.end();
  const int order = cell_order_of(what, dimension, !volume_types.empty(), has_linear, has_quadratic);

  std::vector<std::size_t> node_tags, element_tags, cell_nodes;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(node_tags, coords, parametric, -1, -1, false, false);
  gmsh::model::mesh::getElementsByType(order == 1 ? linear_type : quadratic_type, element_tags, cell_nodes);
  std::unordered_map<std::size_t, std::size_t> position;
  for (std::size_t i = 0; i < node_tags.size(); ++i) position[node_tags[i]] = i;
  for (std::size_t& node : cell_nodes) {
    auto p = position.find(node);
    KERF_CHECK(p != position.end(), what, ": a cell uses node ", node, ", which is not defined");
    node = p->second;
  }
  const std::vector<std::uint64_t> tags(element_tags.begin(), element_tags.end());
  mesh = mesh_from_cells(what, dimension, order, cell_nodes, coords, tags);
}

}  // namespace kerf
