#include "geometry/mesh_division.h"

#include <algorithm>
#include <array>

#include "core/check.h"

namespace kerf {

CellGraph cell_face_graph(const Mesh& mesh) {
  const int corners = mesh.dimension + 1, face_corners = mesh.dimension;
  // Each face of each cell as (its corners sorted, 2D: the last -1; the cell):
  // sorted, the two cells of an inner face follow each other.
  std::vector<std::array<Index, 4>> faces;
  faces.reserve(static_cast<std::size_t>(mesh.cell_count()) * corners);
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    const auto nodes = mesh.cell(c);
    for (int left_out = 0; left_out < corners; ++left_out) {
      std::array<Index, 4> f{-1, -1, -1, c};
      for (int k = 0, at = 0; k < corners; ++k)
        if (k != left_out) f[at++] = nodes[k];
      for (int i = 1; i < face_corners; ++i)  // insertion sort of 2 or 3
        for (int j = i; j > 0 && f[j - 1] > f[j]; --j) std::swap(f[j - 1], f[j]);
      faces.push_back(f);
    }
  }
  std::sort(faces.begin(), faces.end());
  const auto same_face = [](const std::array<Index, 4>& a, const std::array<Index, 4>& b) {
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
  };
  std::vector<std::vector<Index>> around(mesh.cell_count());
  for (std::size_t i = 0; i + 1 < faces.size(); ++i)
    if (same_face(faces[i], faces[i + 1])) {
      around[faces[i][3]].push_back(faces[i + 1][3]);
      around[faces[i + 1][3]].push_back(faces[i][3]);
    }
  CellGraph graph;
  graph.offsets.push_back(0);
  for (std::vector<Index>& list : around) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    graph.neighbours.insert(graph.neighbours.end(), list.begin(), list.end());
    graph.offsets.push_back(static_cast<Index>(graph.neighbours.size()));
  }
  return graph;
}

namespace {

/// The lowest part among each node's cells (part 0 for a node of none).
std::vector<int> node_owners(const Mesh& mesh, std::span<const int> cell_part, int parts) {
  std::vector<int> owner(mesh.node_count(), parts);
  for (Index c = 0; c < mesh.cell_count(); ++c)
    for (Index n : mesh.cell(c)) owner[n] = std::min(owner[n], cell_part[c]);
  for (int& o : owner)
    if (o == parts) o = 0;
  return owner;
}

/// Part p's piece, the nodes numbered `global` across the pieces.
MeshPiece make_piece(const Mesh& mesh, std::span<const int> cell_part, std::span<const int> owner,
                     std::span<const Index> global, std::span<const Index> first_of_part, int p) {
  MeshPiece piece;
  piece.mesh.dimension = mesh.dimension;
  piece.mesh.order = mesh.order;
  piece.first_node = first_of_part[p];
  piece.total_nodes = mesh.node_count();
  piece.total_cells = mesh.cell_count();
  std::vector<char> near(mesh.node_count(), 0);  // a node of an own cell
  for (Index c = 0; c < mesh.cell_count(); ++c)
    if (cell_part[c] == p) {
      piece.source_cell.push_back(c);
      for (Index n : mesh.cell(c)) near[n] = 1;
    }
  piece.own_cells = static_cast<Index>(piece.source_cell.size());
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    if (cell_part[c] == p) continue;
    const auto nodes = mesh.cell(c);
    if (std::any_of(nodes.begin(), nodes.end(), [&](Index n) { return near[n]; })) piece.source_cell.push_back(c);
  }
  // Own nodes in global order (ascending n within a part), then the ghosts in global order.
  std::vector<Index> ghosts;
  for (Index n = 0; n < mesh.node_count(); ++n)
    if (owner[n] == p) piece.global_node.push_back(n);
  piece.own_nodes = static_cast<Index>(piece.global_node.size());
  std::vector<char> local_seen(mesh.node_count(), 0);
  for (Index c : piece.source_cell)
    for (Index n : mesh.cell(c))
      if (owner[n] != p && !local_seen[n]) local_seen[n] = 1, ghosts.push_back(n);
  std::sort(ghosts.begin(), ghosts.end(), [&](Index a, Index b) { return global[a] < global[b]; });
  piece.global_node.insert(piece.global_node.end(), ghosts.begin(), ghosts.end());
  std::vector<Index> local(mesh.node_count(), -1);
  for (Index k = 0; k < static_cast<Index>(piece.global_node.size()); ++k) {
    const Index n = piece.global_node[k];
    local[n] = k;
    piece.mesh.nodes.push_back(mesh.nodes[n]);
    piece.global_node[k] = global[n];
  }
  for (Index c : piece.source_cell)
    for (Index n : mesh.cell(c)) piece.mesh.cells.push_back(local[n]);
  return piece;
}

}  // namespace

std::vector<MeshPiece> divide_mesh(const Mesh& mesh, std::span<const int> cell_part, int parts) {
  KERF_CHECK(static_cast<Index>(cell_part.size()) == mesh.cell_count(), "internal: ", cell_part.size(),
             " parts for ", mesh.cell_count(), " cells");
  const std::vector<int> owner = node_owners(mesh, cell_part, parts);
  std::vector<Index> first_of_part(parts + 1, 0);
  for (int o : owner) ++first_of_part[o + 1];
  for (int p = 0; p < parts; ++p) first_of_part[p + 1] += first_of_part[p];
  std::vector<Index> global(mesh.node_count()), next(first_of_part.begin(), first_of_part.end() - 1);
  for (Index n = 0; n < mesh.node_count(); ++n) global[n] = next[owner[n]]++;
  std::vector<MeshPiece> pieces;
  const auto box = bounding_box(mesh);
  for (int p = 0; p < parts; ++p) {
    pieces.push_back(make_piece(mesh, cell_part, owner, global, first_of_part, p));
    pieces.back().domain_size = (box[1] - box[0]).norm();
  }
  return pieces;
}

std::vector<double> piece_to_numbers(const MeshPiece& piece) {
  const Mesh& m = piece.mesh;
  std::vector<double> out{static_cast<double>(m.dimension),   static_cast<double>(m.order),
                          static_cast<double>(piece.own_cells), static_cast<double>(piece.own_nodes),
                          static_cast<double>(piece.first_node), static_cast<double>(piece.total_nodes),
                          static_cast<double>(piece.total_cells), piece.domain_size,
                          static_cast<double>(m.node_count()),  static_cast<double>(m.cell_count())};
  out.reserve(out.size() + 4 * m.nodes.size() + m.cells.size() + piece.source_cell.size());
  for (const Vec3& x : m.nodes) out.insert(out.end(), x.data(), x.data() + 3);
  out.insert(out.end(), piece.global_node.begin(), piece.global_node.end());
  out.insert(out.end(), piece.source_cell.begin(), piece.source_cell.end());
  out.insert(out.end(), m.cells.begin(), m.cells.end());
  return out;
}

MeshPiece piece_from_numbers(const std::vector<double>& numbers) {
  constexpr std::size_t header = 10;
  KERF_CHECK(numbers.size() >= header, "internal: a mesh piece sent between ranks has no header");
  MeshPiece piece;
  Mesh& m = piece.mesh;
  m.dimension = static_cast<int>(numbers[0]);
  m.order = static_cast<int>(numbers[1]);
  piece.own_cells = static_cast<Index>(numbers[2]);
  piece.own_nodes = static_cast<Index>(numbers[3]);
  piece.first_node = static_cast<Index>(numbers[4]);
  piece.total_nodes = static_cast<Index>(numbers[5]);
  piece.total_cells = static_cast<Index>(numbers[6]);
  piece.domain_size = numbers[7];
  const std::size_t nodes = static_cast<std::size_t>(numbers[8]), cells = static_cast<std::size_t>(numbers[9]);
  const std::size_t entries = cells * static_cast<std::size_t>(m.nodes_per_cell());
  KERF_CHECK(numbers.size() == header + 4 * nodes + cells + entries, "internal: a mesh piece sent between ranks has ",
             numbers.size(), " numbers; its header says ", header + 4 * nodes + cells + entries);
  const double* x = numbers.data() + header;
  for (std::size_t n = 0; n < nodes; ++n) m.nodes.emplace_back(x[3 * n], x[3 * n + 1], x[3 * n + 2]);
  const double* ids = x + 3 * nodes;
  piece.global_node.assign(ids, ids + nodes);
  piece.source_cell.assign(ids + nodes, ids + nodes + cells);
  m.cells.assign(ids + nodes + cells, ids + nodes + cells + entries);
  return piece;
}

}  // namespace kerf
