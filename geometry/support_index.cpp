#include "geometry/support_index.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/check.h"
#include "core/parallel_failure.h"

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

namespace {

/// |d| < r, as reaching() tests it (the norm), with the square root taken
/// only where d's squared length is within round-off of r's square.
inline bool covers(const Vec3& d, double r) {
  const double squared = d.squaredNorm(), limit = r * r;
  if (squared < limit * (1.0 - 1e-12)) return true;
  if (squared > limit * (1.0 + 1e-12)) return false;
  return d.norm() < r;
}

/// The supports covering each query of [begin, end), in groups of
/// `group_size` consecutive queries, appended to `lists` (start relative to
/// its own index). A group's candidates are the nodes reaching a ball around
/// its queries (one search), each query keeps those covering it: the same
/// test as a search of its own, so the same lists.
void append_covering(const SupportIndex& nodes, std::span<const Vec3> queries, Index begin, Index end,
                     Index group_size, double largest_radius, NeighborLists& lists) {
  std::vector<Index> candidates, near;  // not thread_local: in a shared library each use would look its storage up
  const std::vector<Vec3>& position = nodes.positions();
  const std::vector<double>& radius = nodes.radius();
  for (Index first = begin; first < end; first += group_size) {
    const Index last = std::min(end, first + group_size);
    Vec3 centre = Vec3::Zero();
    for (Index q = first; q < last; ++q) centre += queries[q];
    centre /= static_cast<double>(last - first);
    double reach = 0.0;
    for (Index q = first; q < last; ++q) reach = std::max(reach, (queries[q] - centre).norm());
    // |centre - x_I| <= reach + |x - x_I|: a hair more for the norms' round-off.
    if (last - first > 1) nodes.reaching(centre, reach * (1.0 + 1e-9) + 1e-9 * largest_radius, candidates);
    for (Index q = first; q < last; ++q) {
      if (last - first == 1) {
        nodes.reaching(queries[q], 0.0, near);
      } else {
        near.clear();
        for (Index I : candidates)
          if (covers(queries[q] - position[I], radius[I])) near.push_back(I);
      }
      lists.index.insert(lists.index.end(), near.begin(), near.end());
      lists.start.push_back(static_cast<Index>(lists.index.size()));
    }
  }
}

}  // namespace

NeighborLists covering_supports(const SupportIndex& nodes, std::span<const Vec3> queries, Index group_size) {
  KERF_CHECK(group_size >= 1, "internal: queries in groups of ", group_size);
  const Index count = static_cast<Index>(queries.size());
  const Index chunk = group_size * std::max<Index>(1, 256 / group_size);  // whole groups a chunk
  const Index chunks = (count + chunk - 1) / chunk;
  const double largest_radius =
      nodes.radius().empty() ? 0.0 : *std::max_element(nodes.radius().begin(), nodes.radius().end());
  std::vector<NeighborLists> parts(chunks);
  ParallelFailure failure;  // the lists allocate
#pragma omp parallel for schedule(dynamic, 1)
  for (Index c = 0; c < chunks; ++c)
    failure.run([&] {
      append_covering(nodes, queries, c * chunk, std::min(count, (c + 1) * chunk), group_size, largest_radius,
                      parts[c]);
    });
  failure.rethrow_if_failed();
  // Concatenated with each part's place known first (the parts copied in parallel).
  NeighborLists lists;
  lists.start.resize(count + 1);
  std::vector<Index> first_entry(chunks + 1, 0);
  for (Index c = 0; c < chunks; ++c) first_entry[c + 1] = first_entry[c] + static_cast<Index>(parts[c].index.size());
  lists.index.resize(first_entry[chunks]);
#pragma omp parallel for schedule(dynamic, 1)
  for (Index c = 0; c < chunks; ++c) {
    const NeighborLists& part = parts[c];
    std::copy(part.index.begin(), part.index.end(), lists.index.begin() + first_entry[c]);
    for (Index p = 0; p < part.size(); ++p) lists.start[c * chunk + p + 1] = first_entry[c] + part.start[p + 1];
  }
  return lists;
}

}  // namespace kerf
