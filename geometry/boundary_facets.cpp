#include "geometry/boundary_facets.h"

#include <algorithm>

namespace kerf {
namespace {

// Outward corner triples of a positively oriented tetrahedron, and edges of a triangle.
constexpr int tet_faces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
constexpr int tri_edges[3][2] = {{0, 1}, {1, 2}, {2, 0}};

int mid_node(int dimension, int a, int b) {
  auto edges = mid_edge_corners(dimension);
  for (std::size_t k = 0; k < edges.size(); ++k)
    if ((edges[k][0] == a && edges[k][1] == b) || (edges[k][0] == b && edges[k][1] == a))
      return static_cast<int>(k) + (dimension == 3 ? 4 : 3);
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
  const int faces_per_cell = dim == 3 ? 4 : 3;
  const int corners = dim == 3 ? 3 : 2;
  std::vector<Candidate> candidates;
  candidates.reserve(static_cast<std::size_t>(mesh.cell_count()) * faces_per_cell);
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    auto n = mesh.cell(c);
    for (int f = 0; f < faces_per_cell; ++f) {
      std::array<Index, 3> key{-1, -1, -1};
      for (int k = 0; k < corners; ++k) key[k] = n[dim == 3 ? tet_faces[f][k] : tri_edges[f][k]];
      sort_corners(key, corners);
      candidates.push_back({key, c, f});
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.key < b.key; });

  BoundaryFacets out;
  out.nodes_per_facet = dim == 3 ? (mesh.order == 1 ? 3 : 6) : (mesh.order == 1 ? 2 : 3);
  for (std::size_t i = 0; i < candidates.size();) {
    std::size_t j = i + 1;
    while (j < candidates.size() && candidates[j].key == candidates[i].key) ++j;
    if (j - i == 1) {
      const Candidate& cand = candidates[i];
      auto n = mesh.cell(cand.cell);
      int local[3];
      for (int k = 0; k < corners; ++k) local[k] = dim == 3 ? tet_faces[cand.local][k] : tri_edges[cand.local][k];
      for (int k = 0; k < corners; ++k) out.nodes.push_back(n[local[k]]);
      if (mesh.order == 2) {
        if (dim == 3)
          for (int k = 0; k < 3; ++k) out.nodes.push_back(n[mid_node(3, local[k], local[(k + 1) % 3])]);
        else
          out.nodes.push_back(n[mid_node(2, local[0], local[1])]);
      }
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
