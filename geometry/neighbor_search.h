#pragma once
// Neighbour search over a point set (a k-d tree from nanoflann, hidden here),
// and neighbour lists stored once in CSR form.
#include <memory>
#include <span>
#include <vector>

#include "core/types.h"

namespace kerf {

/// Lists of indices, one list per query: list i is index[start[i] .. start[i+1]).
struct NeighborLists {
  std::vector<Index> start{0};
  std::vector<Index> index;
  Index size() const { return static_cast<Index>(start.size()) - 1; }
  std::span<const Index> of(Index i) const {
    return {index.data() + start[i], static_cast<std::size_t>(start[i + 1] - start[i])};
  }
};

/// The transpose of lists over `count` targets: for each target, the slots
/// (positions in lists.index) that hold it, in increasing order. With
/// `entry_list`, also the list holding each entry's slot (entry k of the
/// result's index), written in the same pass.
NeighborLists transpose_slots(const NeighborLists& lists, Index count, std::vector<Index>* entry_list = nullptr);

/// The lists (ascending) that hold one of `targets`, from the transpose
/// (`users`: per target, its slots) and each slot's list (`slot_list`).
std::vector<Index> lists_holding(const NeighborLists& users, std::span<const Index> slot_list, Index list_count,
                                 std::span<const Index> targets);

/// A k-d tree over points (m; 2D points have z = 0).
class PointIndex {
 public:
  explicit PointIndex(std::vector<Vec3> points);
  ~PointIndex();
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  /// The points strictly closer than `radius` to x, in increasing index order
  /// (or, without `in_order`, in the tree's order: a caller that sorts later skips a sort).
  void within(const Vec3& x, double radius, std::vector<Index>& out, bool in_order = true) const;
  const std::vector<Vec3>& points() const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace kerf
