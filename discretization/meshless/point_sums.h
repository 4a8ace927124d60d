#pragma once
// Per-node sums over the points of a shape table, in parallel: the points in
// a fixed number of parts, each part summed into its own array, then the
// parts added in order, so the sums do not depend on the thread count. Each
// part streams through its points' rows (the node arrays are small), which a
// gather by node through the transposed lists does not.
#include <vector>

#include "core/parallel_failure.h"
#include "core/types.h"

namespace kerf {

/// out[j] += what every point adds: term(p, sums) adds point p's
/// contributions into sums (out's size, its part's own), p < points.
template <class PointTerm>
void add_over_points(Index points, std::vector<double>& out, PointTerm term) {
  constexpr Index parts = 4;
  const Index size = static_cast<Index>(out.size());
  std::vector<std::vector<double>> sums(parts);
  ParallelFailure failure;  // the parts allocate, a term may throw
#pragma omp parallel for schedule(static, 1)
  for (Index part = 0; part < parts; ++part)
    failure.run([&] {
      std::vector<double>& mine = sums[part];
      mine.assign(size, 0.0);
      for (Index p = points * part / parts; p < points * (part + 1) / parts; ++p) term(p, mine.data());
    });
  failure.rethrow_if_failed();
#pragma omp parallel for schedule(static)
  for (Index j = 0; j < size; ++j)
    for (Index part = 0; part < parts; ++part) out[j] += sums[part][j];
}

}  // namespace kerf
