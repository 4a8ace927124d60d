#pragma once
// The Delaunay triangulation (CGAL) of a point set as a linear simplex mesh
// (triangles in 2D, z ignored; tetrahedra in 3D) on the points in their order.
// Nodal volumes and the cells of smoothed nodal integration come from it.
#include <span>

#include "geometry/mesh.h"

namespace kerf {

/// Positively oriented cells; throws when two points coincide.
Mesh delaunay_mesh(std::span<const Vec3> points, int dimension);

}  // namespace kerf
