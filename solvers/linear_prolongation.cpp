#include "solvers/linear_prolongation.h"

#include <array>

#include "core/check.h"

namespace kerf {

SparseMatrix corner_prolongation(const Mesh& mesh, const FreeDofs& free, int dofs_per_node,
                                 std::span<const Index> own_nodes) {
  KERF_CHECK(mesh.order == 2, "p-multigrid needs quadratic cells (tet10 or tri6); the mesh has order " +
                                  std::to_string(mesh.order));
  const Index nodes = mesh.node_count();
  const int corners = mesh.dimension + 1;
  const auto edges = mid_edge_corners(mesh.dimension);
  // Each node's coarse dofs: its own (a corner of some cell, or asked for) or its edge's two ends'.
  constexpr Index none = -1;
  std::vector<char> own(static_cast<std::size_t>(nodes), 0);
  for (Index c = 0; c < mesh.cell_count(); ++c)
    for (int k = 0; k < corners; ++k) own[mesh.cell(c)[k]] = 1;
  for (Index n : own_nodes) own[n] = 1;
  std::vector<std::array<Index, 2>> ends(static_cast<std::size_t>(nodes), {none, none});
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    const auto cell = mesh.cell(c);
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const Index middle = cell[corners + static_cast<int>(e)];
      if (!own[middle] && ends[middle][0] == none) ends[middle] = {cell[edges[e][0]], cell[edges[e][1]]};
    }
  }
  std::vector<Index> coarse_of_dof(static_cast<std::size_t>(nodes) * dofs_per_node, none);
  Index coarse = 0;
  for (Index n = 0; n < nodes; ++n)
    if (own[n])
      for (int i = 0; i < dofs_per_node; ++i)
        if (free.free_index(dofs_per_node * n + i) >= 0) coarse_of_dof[dofs_per_node * n + i] = coarse++;
  std::vector<Eigen::Triplet<double, Index>> entries;
  entries.reserve(static_cast<std::size_t>(free.free_count()) * 2);
  for (Index row = 0; row < free.free_count(); ++row) {
    const Index dof = free.free_dofs()[row];
    const Index node = dof / dofs_per_node;
    const int component = static_cast<int>(dof % dofs_per_node);
    if (own[node]) {
      entries.emplace_back(row, coarse_of_dof[dof], 1.0);
      continue;
    }
    for (Index end : ends[node]) {
      if (end == none) continue;  // a node of no cell
      const Index column = coarse_of_dof[dofs_per_node * end + component];
      if (column != none) entries.emplace_back(row, column, 0.5);
    }
  }
  SparseMatrix P(free.free_count(), coarse);
  P.setFromTriplets(entries.begin(), entries.end());
  return P;
}

}  // namespace kerf
