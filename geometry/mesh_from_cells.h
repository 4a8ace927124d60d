#pragma once
// The last steps of reading a mesh file, shared by kerf's own .msh reader and
// gmsh's (geometry/gmsh_session.cpp), so that both give the same Mesh: which
// cells a file's element types make, and the mesh of those cells.
#include <cstdint>
#include <span>
#include <string>

#include "geometry/mesh.h"

namespace kerf {

/// The order of the cells kept (1 or 2), from what the file holds; refuses
/// a 2D scene's file with 3D elements, a file with no cells of `dimension`
/// and one mixing linear and quadratic cells. `what` names the file.
int cell_order_of(const std::string& what, int dimension, bool has_volume_elements, bool has_linear,
                  bool has_quadratic);

/// The mesh of cells given as positions into a node list (x, y, z each; a 2D
/// mesh drops z): the nodes the cells use, numbered in the order the cells
/// first use them; cells oriented positively; a degenerate cell refused,
/// named by its `element_tags` entry.
Mesh mesh_from_cells(const std::string& what, int dimension, int order, std::span<const std::size_t> cell_nodes,
                     std::span<const double> coordinates, std::span<const std::uint64_t> element_tags);

}  // namespace kerf
