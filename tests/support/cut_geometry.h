#pragma once
// Meshes and flat cuts for tests of cuts: structured simplex meshes whose
// grid planes are made of cell faces and hold nodes (for cuts along faces,
// edges and through nodes), cut pieces, and the pieces a split body falls into.
#include <vector>

#include "geometry/cut_surface.h"
#include "geometry/mesh.h"

namespace kerf::testing {

/// [0, n h]^3 as n^3 cubes of edge h, each of 6 Kuhn tetrahedra (one per
/// monotone path along the cube's edges from its lowest to its highest corner).
Mesh kuhn_cubes(int n, double h);

/// The triangle a b c as a cut piece, its normal (b - a) x (c - a).
CutPiece triangle_piece(const Vec3& a, const Vec3& b, const Vec3& c);

/// The plane n . x = d (n.x() != 0) as two triangles over the (y, z) square
/// [-reach, 1 + reach]^2, their normal along n; in 2D (dimension 2) the line
/// n . x = d as one segment over y in [-reach, 1 + reach], its normal along n.
std::vector<CutPiece> plane_cut(int dimension, const Vec3& n, double d, double reach = 0.5);

/// The part of that plane above the front z = front (2D: of the line above
/// y = front), reaching past the unit box elsewhere: a cut with a front
/// inside the box.
std::vector<CutPiece> plane_cut_above(int dimension, const Vec3& n, double d, double front);

/// Each node's piece: the groups of cells joined through shared nodes,
/// numbered from 0 in the order of their lowest node (nodes of no cell: -1).
std::vector<int> node_pieces(const Mesh& mesh);

}  // namespace kerf::testing
