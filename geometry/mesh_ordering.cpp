#include "geometry/mesh_ordering.h"

#include <algorithm>
#include <numeric>
#include <queue>

namespace kerf {

void order_for_locality(Mesh& mesh) {
  const Index n = mesh.node_count();
  if (n == 0) return;
  std::vector<Index> start, adjacent;
  node_adjacency(mesh, start, adjacent);
  auto degree = [&](Index i) { return start[i + 1] - start[i]; };
  // Cuthill-McKee from a node of least degree, breadth first, neighbours by degree;
  // every connected piece in turn.
  std::vector<Index> order;
  order.reserve(n);
  std::vector<char> visited(n, 0);
  std::vector<Index> by_degree(n);
  std::iota(by_degree.begin(), by_degree.end(), 0);
  std::stable_sort(by_degree.begin(), by_degree.end(), [&](Index a, Index b) { return degree(a) < degree(b); });
  std::vector<Index> neighbours;
  for (Index seed : by_degree) {
    if (visited[seed]) continue;
    std::queue<Index> queue;
    queue.push(seed);
    visited[seed] = 1;
    while (!queue.empty()) {
      Index v = queue.front();
      queue.pop();
      order.push_back(v);
      neighbours.assign(adjacent.begin() + start[v], adjacent.begin() + start[v + 1]);
      std::stable_sort(neighbours.begin(), neighbours.end(), [&](Index a, Index b) { return degree(a) < degree(b); });
      for (Index w : neighbours)
        if (!visited[w]) {
          visited[w] = 1;
          queue.push(w);
        }
    }
  }
  std::reverse(order.begin(), order.end());
  std::vector<Index> new_index(n);
  for (Index i = 0; i < n; ++i) new_index[order[i]] = i;
  std::vector<Vec3> nodes(n);
  for (Index i = 0; i < n; ++i) nodes[new_index[i]] = mesh.nodes[i];
  mesh.nodes = std::move(nodes);
  for (Index& v : mesh.cells) v = new_index[v];
  // Cells by their lowest node.
  const int npc = mesh.nodes_per_cell();
  std::vector<Index> cell_order(mesh.cell_count());
  std::iota(cell_order.begin(), cell_order.end(), 0);
  auto lowest = [&](Index c) { return *std::min_element(mesh.cells.begin() + c * npc, mesh.cells.begin() + (c + 1) * npc); };
  std::vector<Index> key(mesh.cell_count());
  for (Index c = 0; c < mesh.cell_count(); ++c) key[c] = lowest(c);
  std::stable_sort(cell_order.begin(), cell_order.end(), [&](Index a, Index b) { return key[a] < key[b]; });
  std::vector<Index> cells(mesh.cells.size());
  for (Index k = 0; k < mesh.cell_count(); ++k)
    std::copy_n(mesh.cells.begin() + cell_order[k] * npc, npc, cells.begin() + k * npc);
  mesh.cells = std::move(cells);
}

}  // namespace kerf
