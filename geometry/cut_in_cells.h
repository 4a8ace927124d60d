#pragma once
// The parts of a cut piece inside the cells of a linear simplex mesh: the
// piece (a 3D triangle, a 2D segment) clipped by each cell it meets, exactly
// (a convex polygon cut by the cell's face planes). The parts of one piece
// partition its part inside the mesh, also where the piece runs along cell
// faces, edges or through nodes: each point of the piece is decided as if
// the piece were moved a hair along its normal, so a piece lying on a face
// belongs to the cell its normal points into, never to both.
#include <span>
#include <vector>

#include "geometry/cut_surface.h"
#include "geometry/mesh.h"

namespace kerf {

/// A piece's part inside one cell: a convex polygon (3D, in order) or a
/// segment (2D, two points), on the piece's own plane or line.
struct CutPart {
  Index cell = -1;
  std::vector<Vec3> corners;
};

/// The cells around each node (CSR over the mesh's nodes).
struct NodeCells {
  std::vector<Index> start{0};
  std::vector<Index> cells;
};
NodeCells node_cells(const Mesh& mesh);

/// The cells that may meet `piece`: those with a corner within `reach` of it
/// (`near_nodes`: the nodes strictly closer than reach to the piece's centre
/// plus its extent; reach at least the longest cell edge).
std::vector<Index> cells_near(const NodeCells& around, std::span<const Index> near_nodes);

/// The piece clipped by each of `cells` (those it meets), `tie` (m) the
/// hair the piece is thought moved along its normal when it lies on a cell's
/// face (1e-9 of the mesh's size is plenty).
std::vector<CutPart> cut_parts(const Mesh& mesh, std::span<const Index> cells, const CutPiece& piece, double tie);

/// A quadrature of a part: 3 points a triangle of its fan (degree 2) in 3D,
/// 2 Gauss points in 2D; weights in m^2 (2D: m), adding up to its measure.
struct PartPoints {
  std::vector<Vec3> position;
  std::vector<double> weight;
};
void part_quadrature(const CutPart& part, int dimension, PartPoints& out);

}  // namespace kerf
