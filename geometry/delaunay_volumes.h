#pragma once
// Nodal volumes of a point set: the Delaunay triangulation (CGAL) of the points,
// each simplex's volume shared equally among its corners. For points that
// fill a convex domain (including its faces and corners) the volumes add up
// to the domain's volume exactly.
#include <span>
#include <vector>

#include "core/types.h"

namespace kerf {

/// Volume (3D, m^3) or area (2D, m^2; z ignored) attributed to each point.
std::vector<double> delaunay_nodal_volumes(std::span<const Vec3> points, int dimension);

}  // namespace kerf
