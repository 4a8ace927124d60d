#pragma once
// The pieces of a 3D cut seen on a common plane, as cut_region and
// CutRegionIndex see them: one definition of "the projection holds x" and of
// "the nearest projected piece", so the two give the same region bit for bit.
#include <array>
#include <limits>

#include <Eigen/Core>

#include "geometry/cut_surface.h"

namespace kerf {

using ProjectedTriangle = std::array<Eigen::Vector2d, 3>;

/// x's coordinates on the frame's plane (axis[0], axis[1]; origin at the frame's).
Eigen::Vector2d in_frame_plane(const CutFrame& frame, const Vec3& x);
ProjectedTriangle projected_piece(const CutPiece& piece, const CutFrame& frame);
/// Does the closed triangle hold q (exact predicate)?
bool projected_holds(const ProjectedTriangle& t, const Eigen::Vector2d& q);
/// The point of the triangle's edges nearest q.
Eigen::Vector2d closest_on_edges(const Eigen::Vector2d& q, const ProjectedTriangle& t);

/// The search's answer: the piece, d+ (0 over it) and the nearest projected point.
struct ProjectedNearest {
  Index piece = 0;
  double distance = std::numeric_limits<double>::infinity();
  Eigen::Vector2d nearest = Eigen::Vector2d::Zero();
};
/// Piece k (triangle t) into `best` if nearer, or as near and earlier (pieces may be visited in any order).
void nearer_projected(Index k, const ProjectedTriangle& t, const Eigen::Vector2d& q, ProjectedNearest& best);
/// Folds piece k into `best`, as cut_region visits pieces in order: true when it holds q (the search ends).
bool visit_projected(Index k, const ProjectedTriangle& t, const Eigen::Vector2d& q, ProjectedNearest& best);
/// The CutRegion of x from the search's answer (d+ and its gradient on the plane, s from the piece).
CutRegion region_from(const CutSurface& cut, const CutFrame& frame, const Vec3& x, const Eigen::Vector2d& q,
                      const ProjectedNearest& best);

}  // namespace kerf
