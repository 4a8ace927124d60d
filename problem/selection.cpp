#include "problem/selection.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "core/check.h"

namespace kerf {

bool Box::contains(const Vec3& p, double tolerance) const {
  for (int i = 0; i < 3; ++i)
    if (p[i] < min[i] - tolerance || p[i] > max[i] + tolerance) return false;
  return true;
}

std::vector<Index> select_points(const Selection& s, std::span<const Vec3> points,
                                 std::span<const char> on_boundary, double domain_size) {
  const double tolerance = 1e-9 * domain_size;
  std::vector<Index> taken;
  if (s.kind == Selection::Kind::point) {
    double best = std::numeric_limits<double>::infinity();
    Index nearest = -1;
    for (std::size_t i = 0; i < points.size(); ++i) {
      double d = (points[i] - s.point).squaredNorm();
      if (d < best) best = d, nearest = static_cast<Index>(i);
    }
    if (nearest >= 0) taken.push_back(nearest);
  } else {
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!on_boundary[i]) continue;
      bool inside = s.kind == Selection::Kind::plane ? std::abs(points[i][s.axis] - s.at) <= tolerance
                                                     : s.box.contains(points[i], tolerance);
      if (inside) taken.push_back(static_cast<Index>(i));
    }
  }
  if (taken.empty()) {
    std::ostringstream what;
    if (s.kind == Selection::Kind::plane)
      what << "the plane " << "xyz"[s.axis] << " = " << s.at;
    else
      what << "the box [" << s.box.min.transpose() << "] .. [" << s.box.max.transpose() << "]";
    throw Error(s.where.describe() + ": the selection takes no boundary points: " + what.str() +
                " touches no point on the body's boundary; expected a selection that touches the body");
  }
  return taken;
}

}  // namespace kerf
