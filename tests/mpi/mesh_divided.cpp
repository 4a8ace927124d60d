// Under mpirun on N ranks (1 to 4): a curved body's tet10 mesh (the organ,
// read from its .msh file on rank 0) divided among the ranks by PT-Scotch:
// every cell is own in exactly one piece, with the nodes and positions of the
// cell as read; the own node ranges tile the new numbering in rank order;
// every cell around an own node is in the piece (the ghost layer is
// complete); every node a piece holds sits where its owner says; the parts
// are balanced. A failure names the rank and what differed.
// usage: mpirun -np N mesh_divided MESH.msh
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "geometry/mesh_from_first_rank.h"
#include "geometry/msh_reader.h"
#include "solvers/petsc_session.h"
#include "solvers/rank_messages.h"

namespace {

int rank_of_process = 0;

void expect(bool ok, const std::string& what) {
  if (ok) return;
  std::fprintf(stderr, "FAILED on rank %d: %s\n", rank_of_process, what.c_str());
  std::exit(1);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace kerf;
  expect(argc == 2, "usage: mesh_divided MESH.msh");
  ensure_petsc_initialized();
  const RankShare ranks = mpi_ranks();
  rank_of_process = ranks.rank;
  const MpiContext mpi = petsc_mpi_context(ranks);
  Mesh whole;  // rank 0's copy of the mesh as read, to compare with
  const MeshPiece piece = mesh_piece_from_first_rank(mpi, [&] {
    whole = read_msh(argv[1], 3, MshOrder::second);
    return whole;
  });
  const Mesh& m = piece.mesh;
  const int npc = m.nodes_per_cell();
  expect(m.order == 2 && npc == 10, "the piece is not of tet10 cells");
  expect(piece.own_cells > 0 && piece.own_nodes > 0, "an empty piece");

  // Own cells: their source index and their nodes' positions, to rank 0.
  std::vector<double> own;
  for (Index c = 0; c < piece.own_cells; ++c) {
    own.push_back(piece.source_cell[c]);
    for (Index n : m.cell(c)) own.insert(own.end(), m.nodes[n].data(), m.nodes[n].data() + 3);
  }
  const auto every_own = mpi.from_every_rank(own);
  if (ranks.rank == 0) {
    std::vector<int> times(whole.cell_count(), 0);
    std::vector<Index> count;
    for (const std::vector<double>& part : every_own) {
      count.push_back(static_cast<Index>(part.size() / (1 + 3 * npc)));
      for (std::size_t at = 0; at < part.size(); at += 1 + 3 * npc) {
        const Index c = static_cast<Index>(part[at]);
        expect(c >= 0 && c < whole.cell_count(), "a piece names cell " + std::to_string(c));
        ++times[c];
        for (int a = 0; a < npc; ++a)
          for (int i = 0; i < 3; ++i)
            expect(part[at + 1 + 3 * a + i] == whole.nodes[whole.cell(c)[a]][i],
                   "cell " + std::to_string(c) + "'s node " + std::to_string(a) + " moved in its piece");
      }
    }
    for (Index c = 0; c < whole.cell_count(); ++c)
      expect(times[c] == 1, "cell " + std::to_string(c) + " is own in " + std::to_string(times[c]) + " pieces");
    const double even = static_cast<double>(whole.cell_count()) / ranks.count;
    for (Index k : count) expect(k <= 1.05 * even + 1, "a part of " + std::to_string(k) + " cells; even is " +
                                                           std::to_string(even));
    std::printf("%d ranks: %d cells, own cells per rank", ranks.count, whole.cell_count());
    for (Index k : count) std::printf(" %d", k);
    std::printf("\n");
  }

  // Own node ranges tile [0, total) in rank order.
  const auto ranges = mpi.from_every_rank({double(piece.first_node), double(piece.own_nodes)});
  Index next = 0;
  for (const auto& r : ranges) {
    expect(r[0] == next, "own nodes start at " + std::to_string(r[0]) + ", expected " + std::to_string(next));
    next += static_cast<Index>(r[1]);
  }
  expect(next == piece.total_nodes, "the own ranges cover " + std::to_string(next) + " of " +
                                        std::to_string(piece.total_nodes) + " nodes");

  // Every node held sits where its owner says (positions joined in rank order).
  std::vector<double> own_positions;
  for (Index n = 0; n < piece.own_nodes; ++n)
    own_positions.insert(own_positions.end(), m.nodes[n].data(), m.nodes[n].data() + 3);
  std::vector<double> positions;
  for (const auto& part : mpi.from_every_rank(own_positions))
    positions.insert(positions.end(), part.begin(), part.end());
  for (Index n = 0; n < m.node_count(); ++n)
    for (int i = 0; i < 3; ++i)
      expect(positions[3 * piece.global_node[n] + i] == m.nodes[n][i],
             "local node " + std::to_string(n) + " is not where its owner has it");

  // Ghost layer: each own node's cells in the piece = its cells over all pieces' own cells.
  std::map<Index, double> valence;  // global node: own cells here around it
  for (Index c = 0; c < piece.own_cells; ++c)
    for (Index n : m.cell(c)) valence[piece.global_node[n]] += 1;
  std::vector<double> pairs;
  for (const auto& [g, k] : valence) pairs.insert(pairs.end(), {double(g), k});
  std::vector<double> total(piece.total_nodes, 0.0);
  for (const auto& part : mpi.from_every_rank(pairs))
    for (std::size_t k = 0; k < part.size(); k += 2) total[static_cast<Index>(part[k])] += part[k + 1];
  std::vector<double> here(m.node_count(), 0.0);
  for (Index c = 0; c < m.cell_count(); ++c)
    for (Index n : m.cell(c)) here[n] += 1;
  for (Index n = 0; n < piece.own_nodes; ++n)
    expect(here[n] == total[piece.first_node + n], "own node " + std::to_string(n) + " has " +
                                                       std::to_string(here[n]) + " cells in the piece, " +
                                                       std::to_string(total[piece.first_node + n]) + " in all");
  std::printf("rank %d: %d own cells, %d ghost cells, %d own nodes, %zu ghost nodes: ok\n", ranks.rank,
              piece.own_cells, m.cell_count() - piece.own_cells, piece.own_nodes,
              m.nodes.size() - static_cast<std::size_t>(piece.own_nodes));
  return 0;
}
