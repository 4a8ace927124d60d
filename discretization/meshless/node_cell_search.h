#pragma once
// The node set's own cells (its linear simplices) found by place, for what a
// cut does to them: the cells a cut piece may meet (the faces of the
// integration constraint's boundary term, the volumes split by a cut) and
// those near a point. Candidates come from the nodes' support index and each
// node's cells; the mesh is passed to each call (its owner may move).
#include <span>
#include <utility>
#include <vector>

#include "geometry/cut_in_cells.h"
#include "geometry/cut_surface.h"
#include "geometry/mesh.h"
#include "geometry/support_index.h"

namespace kerf {

class NodeCellSearch {
 public:
  /// `cells`: the simplices on the nodes `index` holds; `index` must outlive this.
  NodeCellSearch(const Mesh& cells, const SupportIndex& index);

  /// The cells with a corner within `radius` + the longest edge of x: every
  /// cell that reaches within `radius` of x is among them.
  std::vector<Index> near(const Vec3& x, double radius) const;
  /// The cells the piece may meet.
  std::vector<Index> near_piece(const CutPiece& piece, int dimension) const;
  /// Does cell c hold x, its faces included?
  static bool holds(const Mesh& cells, Index c, const Vec3& x);
  /// A cell's centroid and the largest distance of a corner from it.
  static std::pair<Vec3, double> ball(const Mesh& cells, Index c);
  double longest_edge() const { return longest_edge_; }
  const SupportIndex& index() const { return index_; }

 private:
  const SupportIndex& index_;
  NodeCells around_;  // the cells around each node
  double longest_edge_ = 0.0;  // m
};

}  // namespace kerf
