#include "geometry/neighbor_search.h"

#include <nanoflann.hpp>

#include <algorithm>

namespace kerf {

/// nanoflann's dataset adaptor over the point vector.
struct PointIndex::Tree {
  struct Cloud {
    std::vector<Vec3> points;
    std::size_t kdtree_get_point_count() const { return points.size(); }
    double kdtree_get_pt(std::size_t i, std::size_t d) const { return points[i][static_cast<int>(d)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 3, std::size_t>;

  explicit Tree(std::vector<Vec3> points) : cloud{std::move(points)}, tree(3, cloud, {16}) {}
  Cloud cloud;
  KdTree tree;
};

PointIndex::PointIndex(std::vector<Vec3> points) : tree_(std::make_unique<Tree>(std::move(points))) {}
PointIndex::~PointIndex() = default;

const std::vector<Vec3>& PointIndex::points() const { return tree_->cloud.points; }

void PointIndex::within(const Vec3& x, double radius, std::vector<Index>& out, bool in_order) const {
  thread_local std::vector<std::pair<std::size_t, double>> matches;
  matches.clear();
  nanoflann::SearchParams params(32, 0.0f, false);
  tree_->tree.radiusSearch(x.data(), radius * radius, matches, params);
  out.clear();
  for (const auto& m : matches) out.push_back(static_cast<Index>(m.first));
  if (in_order) std::sort(out.begin(), out.end());
}

NeighborLists transpose_slots(const NeighborLists& lists, Index count, std::vector<Index>* entry_list) {
  // Counting sort: slots of a target in list order.
  NeighborLists t;
  t.start.assign(count + 1, 0);
  for (Index K : lists.index) ++t.start[K + 1];
  for (Index K = 0; K < count; ++K) t.start[K + 1] += t.start[K];
  t.index.resize(lists.index.size());
  if (entry_list) entry_list->resize(lists.index.size());
  std::vector<Index> next(t.start.begin(), t.start.end() - 1);
  for (Index l = 0; l < lists.size(); ++l)
    for (Index s = lists.start[l]; s < lists.start[l + 1]; ++s) {
      const Index at = next[lists.index[s]]++;
      t.index[at] = s;
      if (entry_list) (*entry_list)[at] = l;
    }
  return t;
}

std::vector<Index> lists_holding(const NeighborLists& users, std::span<const Index> slot_list, Index list_count,
                                 std::span<const Index> targets) {
  std::vector<char> holds(list_count, 0);
  for (Index K : targets)
    for (Index s : users.of(K)) holds[slot_list[s]] = 1;
  std::vector<Index> lists;
  for (Index i = 0; i < list_count; ++i)
    if (holds[i]) lists.push_back(i);
  return lists;
}

}  // namespace kerf
