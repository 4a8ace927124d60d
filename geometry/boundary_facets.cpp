#include "geometry/boundary_facets.h"

#include <algorithm>

namespace kerf {
namespace {

/// The cell's node on the edge (a, b).
int mid_node(const ElementDescriptor& element, int a, int b) {
  for (std::size_t k = 0; k < element.edges.size(); ++k)
    if ((element.edges[k][0] == a && element.edges[k][1] == b) || (element.edges[k][0] == b && element.edges[k][1] == a))
      return element.dimension + 1 + static_cast<int>(k);
  return -1;
}

// Sorts the first `count` (2 or 3) entries; written out to keep GCC's bounds analysis quiet.
void sort_corners(std::array<Index, 3>& k, int count) {
  if (k[0] > k[1]) std::swap(k[0], k[1]);
  if (count == 2) return;
  if (k[1] > k[2]) std::swap(k[1], k[2]);
  if (k[0] > k[1]) std::swap(k[0], k[1]);
}

struct Candidate {
  std::array<Index, 3> key;  // sorted corner nodes
  Index cell;
  int local;
};

}  // namespace

BoundaryFacets boundary_facets(const Mesh& mesh) {
  const int dim = mesh.dimension;
  const ElementDescriptor& element = element_descriptor(dim, mesh.order);
  const int faces_per_cell = static_cast<int>(element.facets.size());
  const int corners = element.facet_corners;
  std::vector<Candidate> candidates;
  candidates.reserve(static_cast<std::size_t>(mesh.cell_count()) * faces_per_cell);
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    auto n = mesh.cell(c);
    for (int f = 0; f < faces_per_cell; ++f) {
      std::array<Index, 3> key{-1, -1, -1};
      for (int k = 0; k < corners; ++k) key[k] = n[element.facets[f][k]];
      sort_corners(key, corners);
      candidates.push_back({key, c, f});
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.key < b.key; });

  BoundaryFacets out;
  out.nodes_per_facet = element.facet_nodes;
  for (std::size_t i = 0; i < candidates.size();) {
    std::size_t j = i + 1;
    while (j < candidates.size() && candidates[j].key == candidates[i].key) ++j;
    if (j - i == 1) {
      const Candidate& cand = candidates[i];
      auto n = mesh.cell(cand.cell);
      const std::array<int, 3>& local = element.facets[cand.local];
      for (int k = 0; k < corners; ++k) out.nodes.push_back(n[local[k]]);
      // A quadratic facet's mid-edge nodes: a triangle's three edges, an edge's one.
      const int facet_edges = corners == 2 ? 1 : corners;
      if (mesh.order == 2)
        for (int k = 0; k < facet_edges; ++k)
          out.nodes.push_back(n[mid_node(element, local[k], local[(k + 1) % corners])]);
      out.cell.push_back(cand.cell);
    }
    i = j;
  }
  return out;
}

std::vector<char> boundary_node_flags(const Mesh& mesh, const BoundaryFacets& facets) {
  std::vector<char> flags(mesh.nodes.size(), 0);
  for (Index n : facets.nodes) flags[n] = 1;
  return flags;
}

}  // namespace kerf
