#include "geometry/cut_projection.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>

namespace kerf {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = Kernel::Point_2;

Eigen::Vector2d in_frame_plane(const CutFrame& frame, const Vec3& x) {
  const Vec3 d = x - frame.origin;
  return Eigen::Vector2d(frame.axis[0].dot(d), frame.axis[1].dot(d));
}

ProjectedTriangle projected_piece(const CutPiece& piece, const CutFrame& frame) {
  const auto& c = piece.corner;
  return {in_frame_plane(frame, c[0]), in_frame_plane(frame, c[1]), in_frame_plane(frame, c[2])};
}

bool projected_holds(const ProjectedTriangle& t, const Eigen::Vector2d& q) {
  const Kernel::Triangle_2 triangle(Point2(t[0].x(), t[0].y()), Point2(t[1].x(), t[1].y()),
                                    Point2(t[2].x(), t[2].y()));
  return triangle.bounded_side(Point2(q.x(), q.y())) != CGAL::ON_UNBOUNDED_SIDE;
}

Eigen::Vector2d closest_on_edges(const Eigen::Vector2d& q, const ProjectedTriangle& t) {
  Eigen::Vector2d best = t[0];
  double best_distance = std::numeric_limits<double>::infinity();
  for (int e = 0; e < 3; ++e) {
    const Eigen::Vector2d a = t[e], d = t[(e + 1) % 3] - a;
    const double length2 = d.squaredNorm();
    const double u = length2 > 0.0 ? std::clamp((q - a).dot(d) / length2, 0.0, 1.0) : 0.0;
    const Eigen::Vector2d c = a + u * d;
    const double distance = (q - c).squaredNorm();
    if (distance < best_distance) best_distance = distance, best = c;
  }
  return best;
}

void nearer_projected(Index k, const ProjectedTriangle& t, const Eigen::Vector2d& q, ProjectedNearest& best) {
  const Eigen::Vector2d c = closest_on_edges(q, t);
  const double distance = (q - c).norm();
  // An earlier piece wins a tie, whatever the order of the visits.
  if (distance < best.distance || (distance == best.distance && k < best.piece)) best = {k, distance, c};
}

bool visit_projected(Index k, const ProjectedTriangle& t, const Eigen::Vector2d& q, ProjectedNearest& best) {
  if (projected_holds(t, q)) {
    best = {k, 0.0, q};
    return true;
  }
  nearer_projected(k, t, q, best);
  return false;
}

CutRegion region_from(const CutSurface& cut, const CutFrame& frame, const Vec3& x, const Eigen::Vector2d& q,
                      const ProjectedNearest& best) {
  CutRegion r;
  r.piece = best.piece;
  r.d_plus = best.distance;
  if (best.distance > 0.0) {
    const Eigen::Vector2d g = (q - best.nearest) / best.distance;
    r.d_plus_gradient = g.x() * frame.axis[0] + g.y() * frame.axis[1];
  }
  const CutPiece& p = cut.pieces[r.piece];
  r.s = p.normal.dot(x - p.corner[0]);
  r.s_gradient = p.normal;
  return r;
}

}  // namespace kerf
