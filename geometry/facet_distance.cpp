#include "geometry/facet_distance.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <limits>

namespace kerf {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

Kernel::Point_3 point(const Vec3& x) { return {x.x(), x.y(), x.z()}; }

}  // namespace

double distance_to_facets(const Vec3& x, std::span<const std::array<Vec3, 3>> facets) {
  double squared = std::numeric_limits<double>::infinity();
  const Kernel::Point_3 p = point(x);
  for (const auto& [a, b, c] : facets) {
    const double d = b == c ? CGAL::squared_distance(p, Kernel::Segment_3(point(a), point(b)))
                            : CGAL::squared_distance(p, Kernel::Triangle_3(point(a), point(b), point(c)));
    squared = std::min(squared, d);
  }
  return std::sqrt(squared);
}

}  // namespace kerf
