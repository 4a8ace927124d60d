#include "geometry/cut_region_index.h"

#include <algorithm>

namespace kerf {

CutRegionIndex::CutRegionIndex(const CutSurface& cut, Index first, Index last, const CutFrame& frame)
    : cut_(&cut), frame_(&frame), first_(first), last_(last) {
  if (cut.dimension == 2) return;
  for (Index k = first; k < last; ++k) triangles_.push_back(projected_piece(cut.pieces[k], frame));
  for (Index begin = first; begin < last; begin += pieces_per_run) {
    Run run{begin, std::min(last, begin + pieces_per_run), triangles_[begin - first][0], triangles_[begin - first][0]};
    for (Index k = run.first; k < run.last; ++k)
      for (const Eigen::Vector2d& corner : triangles_[k - first])
        run.low = run.low.cwiseMin(corner), run.high = run.high.cwiseMax(corner);
    runs_.push_back(run);
  }
}

bool CutRegionIndex::Run::holds(const Eigen::Vector2d& q) const {
  return (q.array() >= low.array()).all() && (q.array() <= high.array()).all();
}

double CutRegionIndex::Run::distance(const Eigen::Vector2d& q) const {
  return (low - q).cwiseMax(q - high).cwiseMax(0.0).norm();
}

double CutRegionIndex::distance_bound(const Vec3& x) const {
  if (cut_->dimension == 2) return 0.0;
  const Eigen::Vector2d q = in_frame_plane(*frame_, x);
  double bound = std::numeric_limits<double>::infinity();
  for (const Run& run : runs_) bound = std::min(bound, run.distance(q));
  return bound;
}

CutRegion CutRegionIndex::region(const Vec3& x) const {
  if (cut_->dimension == 2) return cut_region(*cut_, first_, last_, *frame_, x);
  const Eigen::Vector2d q = in_frame_plane(*frame_, x);
  // The first piece holding q wins, as in cut_region: only runs whose box holds q can have it.
  for (const Run& run : runs_)
    if (run.holds(q))
      for (Index k = run.first; k < run.last; ++k)
        if (projected_holds(triangles_[k - first_], q)) return region_from(*cut_, *frame_, x, q, {k, 0.0, q});
  // None holds it: the nearest, an earlier piece winning a tie. The runs nearest first, so that the
  // nearest piece is found early and the runs whose box lies farther are passed (their box distance may be
  // rounded the other way by far less than the margin).
  std::vector<std::pair<double, const Run*>> near;
  near.reserve(runs_.size());
  for (const Run& run : runs_) near.emplace_back(run.distance(q), &run);
  std::sort(near.begin(), near.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  ProjectedNearest best;
  for (const auto& [distance, run] : near) {
    if (distance > best.distance * (1.0 + 1e-12)) break;
    for (Index k = run->first; k < run->last; ++k) nearer_projected(k, triangles_[k - first_], q, best);
  }
  return region_from(*cut_, *frame_, x, q, best);
}

}  // namespace kerf
