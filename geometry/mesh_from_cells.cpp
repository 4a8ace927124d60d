#include "geometry/mesh_from_cells.h"

#include <cmath>
#include <limits>
#include <vector>

#include "core/check.h"

namespace kerf {

int cell_order_of(const std::string& what, int dimension, bool has_volume_elements, bool has_linear,
                  bool has_quadratic) {
  // A 3D mesh's boundary triangles are not a plane body.
  KERF_CHECK(dimension != 2 || !has_volume_elements, what, ": holds 3D cells (tetrahedra) but the scene is 2D "
             "(dimension: 2); expected a triangle mesh in the x-y plane, or dimension: 3");
  const int linear_type = element_descriptor(dimension, 1).gmsh_type;
  const int quadratic_type = element_descriptor(dimension, 2).gmsh_type;
  KERF_CHECK(has_linear || has_quadratic, what, ": holds no ", dimension == 3 ? "tetrahedra" : "triangles",
             " (gmsh types ", linear_type, " or ", quadratic_type, ")");
  KERF_CHECK(!(has_linear && has_quadratic), what, ": mixes linear and quadratic cells; expected one order");
  return has_linear ? 1 : 2;
}

Mesh mesh_from_cells(const std::string& what, int dimension, int order, std::span<const std::size_t> cell_nodes,
                     std::span<const double> coordinates, std::span<const std::uint64_t> element_tags) {
  Mesh mesh;
  mesh.dimension = dimension;
  mesh.order = order;
  constexpr Index unused = -1;
  std::vector<Index> local(coordinates.size() / 3, unused);
  mesh.cells.reserve(cell_nodes.size());
  for (std::size_t position : cell_nodes) {
    Index& number = local[position];
    if (number == unused) {
      number = static_cast<Index>(mesh.nodes.size());
      const double* x = &coordinates[3 * position];
      mesh.nodes.emplace_back(x[0], x[1], dimension == 3 ? x[2] : 0.0);
    }
    mesh.cells.push_back(number);
  }
  orient_cells(mesh);
  for (Index c = 0; c < mesh.cell_count(); ++c)
    KERF_CHECK(std::abs(cell_measure(mesh, c)) > 0.0, what, ": cell ", element_tags[static_cast<std::size_t>(c)],
               " is degenerate (zero volume)");
  return mesh;
}

}  // namespace kerf
