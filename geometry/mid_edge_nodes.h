#pragma once
// Linear cells raised to second order on their straight edges, as gmsh's
// setOrder(2) raises a mesh read from a file (no geometry to follow): one
// node at the middle of each edge, shared by the cells around it.
#include <span>
#include <vector>

#include "geometry/mesh.h"

namespace kerf {

/// The quadratic cells of `linear_cells` (positions into `coordinates`, x y z
/// a node): each cell's corners, then its edges' mid-points in gmsh's edge
/// order (core/element_types.h), appended to `coordinates` once an edge.
std::vector<std::size_t> add_mid_edge_nodes(int dimension, std::span<const std::size_t> linear_cells,
                                            std::vector<double>& coordinates);

/// `linear` (order 1) raised the same way: its nodes, then the mid-edge ones.
Mesh with_mid_edge_nodes(const Mesh& linear);

}  // namespace kerf
