#pragma once
// cut_region over a 3D cut of many pieces, at a cost that does not grow with
// them: the pieces projected once on the common plane, in runs of
// consecutive pieces (neighbours along a strip) with a box each, so that a
// query visits the runs whose box holds its point or lies nearer than the
// nearest piece found so far. Same answer as cut_region, bit for bit (the
// same visits in the same order, less those that cannot win); a 2D cut is
// passed on to cut_region.
#include <vector>

#include "geometry/cut_projection.h"

namespace kerf {

class CutRegionIndex {
 public:
  /// Pieces [first, last) of `cut`, seen in `frame`; both are viewed, not copied.
  CutRegionIndex(const CutSurface& cut, Index first, Index last, const CutFrame& frame);
  CutRegion region(const Vec3& x) const;
  /// A distance on the plane (m) that no piece's projection is nearer x than.
  double distance_bound(const Vec3& x) const;

  static constexpr Index pieces_per_run = 16;

 private:
  struct Run {
    Index first = 0, last = 0;  // pieces
    Eigen::Vector2d low, high;  // box of their projections
    bool holds(const Eigen::Vector2d& q) const;
    double distance(const Eigen::Vector2d& q) const;  // 0 inside
  };
  const CutSurface* cut_;
  const CutFrame* frame_;
  Index first_, last_;
  std::vector<ProjectedTriangle> triangles_;  // piece first_ + i
  std::vector<Run> runs_;
};

}  // namespace kerf
