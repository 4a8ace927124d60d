#pragma once
// Nodes with supports of their own radius, for "which supports reach x".
#include <memory>
#include <span>
#include <vector>

#include "core/types.h"
#include "geometry/neighbor_search.h"

namespace kerf {

/// The nodes are grouped by support radius (within a factor 2 of each other)
/// and each group is searched with its own largest radius: on a graded node
/// set one search with the set's largest radius gathers, at a fine node,
/// every node of the coarse levels around it (thousands, then sorted), which
/// made EFG's set-up grow as the square of the node count.
class SupportIndex {
 public:
  SupportIndex(std::vector<Vec3> positions, std::vector<double> radius);
  ~SupportIndex();
  SupportIndex(const SupportIndex&) = delete;
  SupportIndex& operator=(const SupportIndex&) = delete;

  /// The nodes I with |x - x_I| < radius[I] + extra, in increasing order
  /// (extra = 0: the supports covering x); without `in_order`, in any order.
  void reaching(const Vec3& x, double extra, std::vector<Index>& out, bool in_order = true) const;
  /// The nodes strictly closer than `distance` to x, in increasing order.
  void within(const Vec3& x, double distance, std::vector<Index>& out) const;
  const std::vector<Vec3>& positions() const { return positions_; }
  const std::vector<double>& radius() const { return radius_; }

 private:
  struct Group;
  std::vector<Vec3> positions_;
  std::vector<double> radius_;
  std::vector<Group> groups_;
};

/// For each query point x, the nodes I whose support covers it: |x - x_I| <
/// radius[I], in increasing order; queries in parallel. With `group_size` > 1,
/// each run of that many consecutive queries (a cell's Gauss points) shares one
/// search for the nodes reaching a ball around them: the same lists, fewer
/// searches where the queries lie close together.
NeighborLists covering_supports(const SupportIndex& nodes, std::span<const Vec3> queries, Index group_size = 1);

}  // namespace kerf
