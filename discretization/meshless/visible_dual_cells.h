#pragma once
// Nodal volumes that see the cuts. A node's barycentric dual cell (its nodal
// volume, NSNI's second moments) can reach across a cut, where the node's
// enriched shape function is zero: nodal integration would then weigh the far
// side's material with the near side's strain, and the far side would miss
// it. Here each part of a cell that a cut crosses goes to the corner nearest
// it (largest barycentric coordinate) among the corners that see it: the
// segment from the corner to the point crosses no cut piece, a corner lying
// on a piece looking from the piece's + side (the convention of cut_phi.h,
// where such a node's weight lives). The volumes still add up to the body's.
// The parts' boundaries are found by refining the barycentric subdivision's
// simplices where the owners of their corners differ, `depth` times.
#include <span>
#include <unordered_map>
#include <vector>

#include "geometry/cut_surface.h"
#include "geometry/mesh.h"

namespace kerf {

/// Does the piece meet cell c of `cells` (touching, within `tie` m, counts)?
bool piece_meets_cell(const CutPiece& piece, const Mesh& cells, Index c, double tie);

class VisibleDualCells {
 public:
  /// The dual cells of `cells` (linear simplices on the nodes), no cut yet.
  explicit VisibleDualCells(const Mesh& cells, int depth = 4);

  /// Recomputes the cells of `cells` (the same mesh) in `near` (those a piece
  /// may meet) against `pieces` (every piece present, of every cut). Returns
  /// the nodes whose volume changed.
  std::vector<Index> update(const Mesh& cells, std::span<const Index> near, std::span<const CutPiece> pieces);

  /// A corner's part of one cell: its volume (m^3; 2D m^2), first moment
  /// int x (m^4), second moments about the corner int (x_i - x_corner,i)^2.
  struct Share {
    double volume = 0.0;
    Vec3 first = Vec3::Zero();
    Vec3 moment = Vec3::Zero();
  };
  using CellShares = std::array<Share, 4>;  // per corner
  /// Cell c's parts as they stand (split by the cuts, or the plain dual ones).
  CellShares shares(const Mesh& cells, Index c) const;
  /// The cells a cut splits (some part handed to another corner), ascending.
  std::vector<Index> split_cells() const;

  const std::vector<double>& volume() const { return volume_; }
  /// int (x_i - x_I,i)^2 over node I's part (m^5; 2D m^4; z = 0).
  const std::vector<Vec3>& second_moment() const { return moment_; }

 private:
  CellShares visible_parts(const Mesh& cells, Index c, std::span<const CutPiece* const> pieces) const;

  int depth_;
  std::vector<double> volume_;
  std::vector<Vec3> moment_;
  std::unordered_map<Index, CellShares> split_;  // the cells whose shares a cut changed
};

}  // namespace kerf
