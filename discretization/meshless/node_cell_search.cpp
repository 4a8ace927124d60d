#include "discretization/meshless/node_cell_search.h"

#include <algorithm>

namespace kerf {

NodeCellSearch::NodeCellSearch(const Mesh& cells, const SupportIndex& index)
    : index_(index), around_(node_cells(cells)) {
  const int corners = cells.dimension + 1;
  for (Index c = 0; c < cells.cell_count(); ++c)
    for (int a = 0; a < corners; ++a)
      for (int b = a + 1; b < corners; ++b)
        longest_edge_ =
            std::max(longest_edge_, (cells.nodes[cells.cell(c)[a]] - cells.nodes[cells.cell(c)[b]]).norm());
}

std::vector<Index> NodeCellSearch::near(const Vec3& x, double radius) const {
  std::vector<Index> nodes;
  index_.within(x, radius + longest_edge_, nodes);
  return cells_near(around_, nodes);
}

std::vector<Index> NodeCellSearch::near_piece(const CutPiece& piece, int dimension) const {
  double reach = 0.0;
  for (int k = 0; k < dimension; ++k) reach = std::max(reach, (piece.corner[k] - piece.centre).norm());
  return near(piece.centre, reach);
}

bool NodeCellSearch::holds(const Mesh& cells, Index c, const Vec3& x) {
  const int dim = cells.dimension;
  auto n = cells.cell(c);
  Mat3 edges = Mat3::Identity();
  for (int k = 1; k <= dim; ++k) edges.col(k - 1) = cells.nodes[n[k]] - cells.nodes[n[0]];
  const Vec3 l = edges.inverse() * (x - cells.nodes[n[0]]);
  const double tolerance = 1e-9;
  double sum = 0.0;
  for (int k = 0; k < dim; ++k) {
    if (l[k] < -tolerance) return false;
    sum += l[k];
  }
  return sum <= 1.0 + tolerance;
}

std::pair<Vec3, double> NodeCellSearch::ball(const Mesh& cells, Index c) {
  const int corners = cells.dimension + 1;
  auto n = cells.cell(c);
  Vec3 centre = Vec3::Zero();
  for (int k = 0; k < corners; ++k) centre += cells.nodes[n[k]] / corners;
  double radius = 0.0;
  for (int k = 0; k < corners; ++k) radius = std::max(radius, (cells.nodes[n[k]] - centre).norm());
  return {centre, radius};
}

}  // namespace kerf
