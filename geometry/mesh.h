#pragma once
// A simplex mesh as flat arrays. Node order within a cell is gmsh's:
//   tet10 mid-edge nodes 4..9 on edges (0,1) (1,2) (0,2) (0,3) (2,3) (1,3);
//   tri6  mid-edge nodes 3..5 on edges (0,1) (1,2) (0,2).
// Cells are positively oriented (tets: positive volume; triangles: counter-clockwise).
#include <array>
#include <functional>
#include <span>
#include <vector>

#include "core/element_types.h"
#include "core/types.h"

namespace kerf {

enum class CellShape { tetrahedron, triangle };

struct Mesh {
  int dimension = 3;       // 3: tetrahedra; 2: triangles in the x-y plane
  int order = 1;           // 1: linear cells; 2: quadratic (mid-edge nodes)
  std::vector<Vec3> nodes; // reference positions (m), N
  std::vector<Index> cells;  // C * nodes_per_cell()

  int nodes_per_cell() const;
  Index cell_count() const { return static_cast<Index>(cells.size() / nodes_per_cell()); }
  Index node_count() const { return static_cast<Index>(nodes.size()); }
  std::span<const Index> cell(Index c) const {
    return {cells.data() + static_cast<std::size_t>(c) * nodes_per_cell(),
            static_cast<std::size_t>(nodes_per_cell())};
  }
};

/// The local edge (pair of corners) that carries mid-edge node 4+k (tets) or 3+k (triangles).
std::span<const std::array<int, 2>> mid_edge_corners(int dimension);

/// Flips negatively oriented cells in place; returns how many were flipped.
Index orient_cells(Mesh& mesh);

/// Volume (3D) or area (2D) of the straight-sided cell c.
double cell_measure(const Mesh& mesh, Index c);

/// Each node's share of the straight-sided cells around it (1/corners of each),
/// i.e. the measure of its barycentric dual cell; nodes of no cell get 0.
std::vector<double> dual_cell_volumes(const Mesh& mesh);

/// int_S (x_i - p_i)^2 over the simplex S with corners p + y_k, of measure
/// `measure`: |S| / ((dim + 1)(dim + 2)) (sum_k y_k y_k^T + s s^T)_ii, s = sum_k y_k.
Vec3 simplex_second_moment(std::span<const Vec3> y, double measure);

/// The barycentric subdivision of the straight-sided cell c, piece by piece:
/// visit(a, vertices, measure) for each of corner a's dim! simplices (the
/// corner, an edge midpoint, a face centroid[, the cell's centroid]), which
/// together are corner a's part of its dual cell.
using BarycentricPieceVisitor = std::function<void(int corner, std::span<const Vec3> vertices, double measure)>;
void for_each_barycentric_piece(const Mesh& mesh, Index c, const BarycentricPieceVisitor& visit);

/// Each node's second moments of its barycentric dual cell about the node
/// itself, int (x_i - x_node,i)^2 over the cell (m^5; 2D: m^4; z = 0), exact:
/// the dual part of a corner in a simplex is the union of the barycentric
/// subdivision's simplices at that corner (corner, edge midpoint, face
/// centroid[, cell centroid]), each integrated in closed form.
std::vector<Vec3> dual_cell_second_moments(const Mesh& mesh);

/// Each node's neighbours (the other nodes of its cells), ascending, in CSR
/// form: node i's are adjacent[start[i], start[i + 1]).
void node_adjacency(const Mesh& mesh, std::vector<Index>& start, std::vector<Index>& adjacent);

/// The straight-sided linear mesh on the corners of each cell: mid-edge nodes
/// and nodes of no cell dropped, the others kept in their original order.
Mesh corner_mesh(const Mesh& mesh);

/// Smallest axis-aligned box holding every node.
std::array<Vec3, 2> bounding_box(const Mesh& mesh);

}  // namespace kerf
