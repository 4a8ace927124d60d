#pragma once
// A mesh divided among MPI ranks, made on rank 0 from the whole mesh and a
// part for each cell (a partitioner's choice on the cells' face graph): each
// part's piece holds its own cells, then one layer of ghost cells (every
// other cell that shares a node with one of its own), on local nodes
// numbered own-first. Every cell is own in exactly one piece. The nodes are
// numbered anew across the pieces so that each piece's own nodes are one
// contiguous range, the pieces in part order: those are its rows. A node
// belongs to the lowest part among its cells' (a node of no cell, to part 0).
// With the ghost layer, every cell around an own node is in the piece, so
// an own node's boundary flag, loads, gravity and mass are complete there.
#include <span>
#include <vector>

#include "geometry/mesh.h"

namespace kerf {

/// The cells' face graph: cells are neighbours when they share a face (3D:
/// three corners; 2D: an edge), as sorted lists without the cell itself.
struct CellGraph {
  std::vector<Index> offsets;     // cells + 1
  std::vector<Index> neighbours;
};
CellGraph cell_face_graph(const Mesh& mesh);

struct MeshPiece {
  Mesh mesh;              // own cells first, then ghost cells; own nodes first (ascending global number), then ghosts
  Index own_cells = 0;
  Index own_nodes = 0;
  Index first_node = 0;   // global number of own node 0: own node k is first_node + k
  Index total_nodes = 0;  // of the whole mesh
  Index total_cells = 0;
  double domain_size = 0.0;        // the whole mesh's bounding-box diagonal (m)
  std::vector<Index> global_node;  // per local node: its number across the pieces
  std::vector<Index> source_cell;  // per local cell: its index in the whole mesh
};

/// The pieces of `mesh` for `parts` parts, cell c going to part cell_part[c].
std::vector<MeshPiece> divide_mesh(const Mesh& mesh, std::span<const int> cell_part, int parts);

/// A piece as numbers to send between ranks, and back (indices exact below 2^53).
std::vector<double> piece_to_numbers(const MeshPiece& piece);
MeshPiece piece_from_numbers(const std::vector<double>& numbers);

}  // namespace kerf
