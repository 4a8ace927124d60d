#include "geometry/support_index.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace kerf {

struct SupportIndex::Group {
  std::vector<Index> node;  // the group's nodes, ascending
  double largest = 0.0;
  std::unique_ptr<PointIndex> index;  // over the group's positions
};

SupportIndex::SupportIndex(std::vector<Vec3> positions, std::vector<double> radius)
    : positions_(std::move(positions)), radius_(std::move(radius)) {
  if (radius_.empty()) return;
  const double smallest = *std::min_element(radius_.begin(), radius_.end());
  std::map<int, Group> by_octave;  // floor(log2(r / smallest)): radii within a factor 2
  for (Index I = 0; I < static_cast<Index>(radius_.size()); ++I) {
    const int octave = smallest > 0.0 ? static_cast<int>(std::floor(std::log2(radius_[I] / smallest))) : 0;
    Group& g = by_octave[octave];
    g.node.push_back(I);
    g.largest = std::max(g.largest, radius_[I]);
  }
  for (auto& [octave, g] : by_octave) {
    std::vector<Vec3> points;
    points.reserve(g.node.size());
    for (Index I : g.node) points.push_back(positions_[I]);
    g.index = std::make_unique<PointIndex>(std::move(points));
    groups_.push_back(std::move(g));
  }
}

SupportIndex::~SupportIndex() = default;

void SupportIndex::reaching(const Vec3& x, double extra, std::vector<Index>& out, bool in_order) const {
  thread_local std::vector<Index> local;
  out.clear();
  for (const Group& g : groups_) {
    g.index->within(x, g.largest + extra, local, in_order);
    for (Index k : local) {
      const Index I = g.node[k];
      if ((x - positions_[I]).norm() < radius_[I] + extra) out.push_back(I);
    }
  }
  if (in_order && groups_.size() > 1) std::sort(out.begin(), out.end());
}

void SupportIndex::within(const Vec3& x, double distance, std::vector<Index>& out) const {
  thread_local std::vector<Index> local;
  out.clear();
  for (const Group& g : groups_) {
    g.index->within(x, distance, local);
    for (Index k : local) out.push_back(g.node[k]);
  }
  if (groups_.size() > 1) std::sort(out.begin(), out.end());
}

NeighborLists covering_supports(const SupportIndex& nodes, std::span<const Vec3> queries) {
  NeighborLists lists;
  std::vector<Index> near;
  for (const Vec3& x : queries) {
    nodes.reaching(x, 0.0, near);
    lists.index.insert(lists.index.end(), near.begin(), near.end());
    lists.start.push_back(static_cast<Index>(lists.index.size()));
  }
  return lists;
}

}  // namespace kerf
