#include "geometry/gmsh_session.h"

#include <gmsh.h>

#include <unordered_map>

#include "core/check.h"
#include "core/thread_scope.h"

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
  std::vector<int> types;
  if (dimension == 2) {  // a 3D mesh's boundary triangles are not a plane body
    gmsh::model::mesh::getElementTypes(types, 3);
    KERF_CHECK(types.empty(), what, ": holds 3D cells (tetrahedra) but the scene is 2D (dimension: 2); expected a "
               "triangle mesh in the x-y plane, or dimension: 3");
  }
  gmsh::model::mesh::getElementTypes(types, dimension);
  const int linear_type = element_descriptor(dimension, 1).gmsh_type;
  const int quadratic_type = element_descriptor(dimension, 2).gmsh_type;
  bool has_linear = std::find(types.begin(), types.end(), linear_type) != types.end();
  bool has_quadratic = std::find(types.begin(), types.end(), quadratic_type) != types.end();
  KERF_CHECK(has_linear || has_quadratic, what, ": holds no ", dimension == 3 ? "tetrahedra" : "triangles",
             " (gmsh types ", linear_type, " or ", quadratic_type, ")");
  KERF_CHECK(!(has_linear && has_quadratic), what, ": mixes linear and quadratic cells; expected one order");
  mesh.dimension = dimension;
  mesh.order = has_linear ? 1 : 2;

  std::vector<std::size_t> node_tags, element_tags, cell_nodes;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(node_tags, coords, parametric, -1, -1, false, false);
  gmsh::model::mesh::getElementsByType(has_linear ? linear_type : quadratic_type, element_tags, cell_nodes);

  // Keep only the nodes the cells use, numbered in first-use order.
  std::unordered_map<std::size_t, std::size_t> position;
  for (std::size_t i = 0; i < node_tags.size(); ++i) position[node_tags[i]] = i;
  std::unordered_map<std::size_t, Index> local;
  mesh.nodes.clear();
  mesh.cells.clear();
  mesh.cells.reserve(cell_nodes.size());
  for (std::size_t tag : cell_nodes) {
    auto [it, inserted] = local.try_emplace(tag, static_cast<Index>(mesh.nodes.size()));
    if (inserted) {
      auto p = position.find(tag);
      KERF_CHECK(p != position.end(), what, ": a cell uses node ", tag, ", which is not defined");
      const double* x = &coords[3 * p->second];
      mesh.nodes.emplace_back(x[0], x[1], dimension == 3 ? x[2] : 0.0);
    }
    mesh.cells.push_back(it->second);
  }
  orient_cells(mesh);
  for (Index c = 0; c < mesh.cell_count(); ++c)
    KERF_CHECK(std::abs(cell_measure(mesh, c)) > 0.0, what, ": cell ", element_tags[c],
               " is degenerate (zero volume)");
}

}  // namespace kerf
