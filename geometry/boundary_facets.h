#pragma once
// The boundary of a simplex mesh: faces (3D, tri3/tri6) or edges (2D, line2/line3)
// that belong to one cell only, oriented with the outward normal.
#include <vector>

#include "geometry/mesh.h"

namespace kerf {

struct BoundaryFacets {
  int nodes_per_facet = 3;     // 3D: 3 or 6; 2D: 2 or 3 (corners first, then mid-edge nodes)
  std::vector<Index> nodes;    // F * nodes_per_facet
  std::vector<Index> cell;     // F: the cell each facet bounds
  Index count() const { return static_cast<Index>(cell.size()); }
  std::span<const Index> facet(Index f) const {
    return {nodes.data() + static_cast<std::size_t>(f) * nodes_per_facet,
            static_cast<std::size_t>(nodes_per_facet)};
  }
};

BoundaryFacets boundary_facets(const Mesh& mesh);

/// 1 for every node on a boundary facet, 0 otherwise (N).
std::vector<char> boundary_node_flags(const Mesh& mesh, const BoundaryFacets& facets);

}  // namespace kerf
