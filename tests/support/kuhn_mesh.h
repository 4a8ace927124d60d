#pragma once
// Structured simplex meshes whose grid planes are made of cell faces and hold
// nodes, for cuts that run along faces, edges and through nodes; and a cut
// piece from three corners.
#include "geometry/cut_surface.h"
#include "geometry/mesh.h"

namespace kerf::testing {

/// [0, n h]^3 as n^3 cubes of edge h, each of 6 Kuhn tetrahedra (one per
/// monotone path along the cube's edges from its lowest to its highest corner).
Mesh kuhn_cubes(int n, double h);

/// The triangle a b c as a cut piece, its normal (b - a) x (c - a).
CutPiece triangle_piece(const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace kerf::testing
