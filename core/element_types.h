#pragma once
// Every cell type kerf meshes with, described once: the scene's name, its
// dimension and polynomial order, its nodes (corners first, then one on each
// edge in `edges` order: gmsh's numbering), its facets, the gmsh element type
// it is read as, the VTK cell type and node order it is written in, and what
// the FEM body and the resource estimate need of it.
// A new simplex type is a row here (and its shape functions in
// discretization/fem/simplex_shape.h); every other file asks this table.
#include <array>
#include <span>

#include "core/enum_table.h"

namespace kerf {

enum class ElementType { tet4, tet10, tri3, tri6 };

struct ElementDescriptor {
  ElementType type;
  const char* name;  // the scene file's spelling (discretization.fem.element)
  int dimension;
  int order;
  int nodes;    // per cell: the corners (dimension + 1), then one per edge when quadratic
  int gmsh_type;  // gmsh's element type number
  int vtk_type;   // VTK's cell type (VTK_TETRA, VTK_QUADRATIC_TETRA, ...)
  /// The cell's node written at each of VTK's positions (VTK's quadratic
  /// tetrahedron takes the edges (1,3) and (2,3) in the other order).
  std::span<const int> vtk_nodes;
  /// The corner pairs of the edges, in the order of the mid-edge nodes that
  /// follow the corners (every edge of the simplex, also for linear cells).
  std::span<const std::array<int, 2>> edges;
  /// Each facet's corners, outward for a positively oriented cell (3D: triangles, 2D: edges).
  std::span<const std::array<int, 3>> facets;
  int facet_corners;  // 3 (3D) or 2 (2D)
  int facet_nodes;    // corners first, then the mid-edge nodes of a quadratic facet
  /// The degree the stiffness quadrature integrates exactly: 2 (order - 1).
  int stiffness_degree;
  /// Nodes a matrix row couples on a typical mesh, itself included (the
  /// resource estimate's; measured on gmsh meshes of the studies' boxes).
  double coupled_nodes;
};

namespace element_detail {
inline constexpr std::array<std::array<int, 2>, 6> tet_edges{{{0, 1}, {1, 2}, {0, 2}, {0, 3}, {2, 3}, {1, 3}}};
inline constexpr std::array<std::array<int, 2>, 3> tri_edges{{{0, 1}, {1, 2}, {0, 2}}};
inline constexpr std::array<std::array<int, 3>, 4> tet_facets{{{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};
inline constexpr std::array<std::array<int, 3>, 3> tri_facets{{{0, 1, -1}, {1, 2, -1}, {2, 0, -1}}};
inline constexpr std::array<int, 4> tet4_vtk{0, 1, 2, 3};
inline constexpr std::array<int, 10> tet10_vtk{0, 1, 2, 3, 4, 5, 6, 7, 9, 8};
inline constexpr std::array<int, 3> tri3_vtk{0, 1, 2};
inline constexpr std::array<int, 6> tri6_vtk{0, 1, 2, 3, 4, 5};
}  // namespace element_detail

/// Every element type, in ElementType's order.
inline constexpr std::array<ElementDescriptor, 4> element_types{{
    {ElementType::tet4, "tet4", 3, 1, 4, 4, 10, element_detail::tet4_vtk, element_detail::tet_edges,
     element_detail::tet_facets, 3, 3, 0, 15.0},
    {ElementType::tet10, "tet10", 3, 2, 10, 11, 24, element_detail::tet10_vtk, element_detail::tet_edges,
     element_detail::tet_facets, 3, 6, 2, 27.0},
    {ElementType::tri3, "tri3", 2, 1, 3, 2, 5, element_detail::tri3_vtk, element_detail::tri_edges,
     element_detail::tri_facets, 2, 2, 0, 7.0},
    {ElementType::tri6, "tri6", 2, 2, 6, 9, 22, element_detail::tri6_vtk, element_detail::tri_edges,
     element_detail::tri_facets, 2, 3, 2, 14.0},
}};

static_assert(rows_follow_enum(element_types, &ElementDescriptor::type),
              "element_types: one row per ElementType, in its order");

constexpr const ElementDescriptor& element_descriptor(ElementType type) { return row_of(element_types, type); }

/// The simplex of `dimension` (2, 3) and `order` (1, 2): what a mesh of that kind holds.
constexpr const ElementDescriptor& element_descriptor(int dimension, int order) {
  for (const ElementDescriptor& e : element_types)
    if (e.dimension == dimension && e.order == order) return e;
  return element_types[0];  // unreachable for the dimensions and orders a Mesh holds
}

}  // namespace kerf
