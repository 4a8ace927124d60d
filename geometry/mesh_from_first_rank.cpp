#include "geometry/mesh_from_first_rank.h"

#include <malloc.h>

#include "core/check.h"
#include "core/mpi_context.h"

namespace kerf {

std::vector<double> mesh_to_numbers(const Mesh& mesh) {
  // Header: dimension, order, node count, cell entries; then x y z per node and
  // the cells' node indices (exact as doubles: below 2^53).
  std::vector<double> numbers{static_cast<double>(mesh.dimension), static_cast<double>(mesh.order),
                              static_cast<double>(mesh.nodes.size()), static_cast<double>(mesh.cells.size())};
  numbers.reserve(4 + 3 * mesh.nodes.size() + mesh.cells.size());
  for (const Vec3& x : mesh.nodes) numbers.insert(numbers.end(), x.data(), x.data() + 3);
  numbers.insert(numbers.end(), mesh.cells.begin(), mesh.cells.end());
  return numbers;
}

Mesh mesh_from_numbers(const std::vector<double>& numbers) {
  KERF_CHECK(numbers.size() >= 4, "internal: a mesh sent between ranks has no header");
  Mesh mesh;
  mesh.dimension = static_cast<int>(numbers[0]);
  mesh.order = static_cast<int>(numbers[1]);
  const std::size_t nodes = static_cast<std::size_t>(numbers[2]), entries = static_cast<std::size_t>(numbers[3]);
  KERF_CHECK(numbers.size() == 4 + 3 * nodes + entries, "internal: a mesh sent between ranks has ",
             numbers.size(), " numbers; its header says ", 4 + 3 * nodes + entries);
  mesh.nodes.resize(nodes);
  const double* x = numbers.data() + 4;
  for (std::size_t n = 0; n < nodes; ++n) mesh.nodes[n] = Vec3(x[3 * n], x[3 * n + 1], x[3 * n + 2]);
  const double* cells = x + 3 * nodes;
  mesh.cells.assign(cells, cells + entries);
  return mesh;
}

Mesh mesh_from_first_rank(const MpiContext& mpi, const std::function<Mesh()>& make) {
  if (!mpi.distributed()) return make();
  if (mpi.ranks.rank == 0) {
    Mesh mesh = make();
    mpi.from_first_rank(mesh_to_numbers(mesh));
    return mesh;
  }
  return mesh_from_numbers(mpi.from_first_rank({}));
}

MeshPiece mesh_piece_from_first_rank(const MpiContext& mpi, const std::function<Mesh()>& make) {
  if (!mpi.distributed()) {
    Mesh mesh = make();
    return divide_mesh(mesh, std::vector<int>(mesh.cell_count(), 0), 1).front();
  }
  KERF_CHECK(mpi.partition && mpi.send_parts, "internal: a mesh divided among ranks without a partitioner");
  std::vector<std::vector<double>> numbers;
  if (mpi.ranks.rank == 0) {
    std::vector<MeshPiece> pieces;
    {
      const Mesh mesh = make();
      const CellGraph graph = cell_face_graph(mesh);
      const std::vector<int> parts = mpi.partition(graph.offsets, graph.neighbours, mpi.ranks.count);
      pieces = divide_mesh(mesh, parts, mpi.ranks.count);
    }
    for (MeshPiece& piece : pieces) {
      numbers.push_back(piece_to_numbers(piece));
      piece = MeshPiece{};
    }
  }
  MeshPiece mine = piece_from_numbers(mpi.part_from_first_rank(std::move(numbers)));
  // The whole mesh was many small blocks: give them back to the system, or
  // rank 0 would keep the whole mesh's memory in its footprint.
  if (mpi.ranks.rank == 0) malloc_trim(0);
  return mine;
}

}  // namespace kerf
