#pragma once
// The two fragments of a simplex that a flat cut separates, as sub-simplices:
// the marching-tetrahedra table by the corners' sides (+, -, or 0 for a corner
// on the cut) and the points where the cut crosses the edges between a + and a
// - corner. 3D: a lone corner's tet against a prism (1-3), two prisms (2-2),
// a tet against a pyramid (1-2 with a corner on the cut), two tets (1-1 with
// two on it). 2D: a triangle against a quadrilateral, or two triangles.
// Every sub-simplex is positively oriented; the two sides tile the cell.
#include <array>
#include <functional>
#include <vector>

#include "core/types.h"

namespace kerf {

struct CellFragments {
  /// (dim + 1) points per sub-simplex; [0]: the + side, [1]: the - side.
  std::array<std::vector<Vec3>, 2> simplices;
};

/// `corners`: the cell's dim + 1 corners; `sides`: -1, 0 or +1 per corner,
/// with at least one +1 and one -1; `crossing(a, b)`: the point on edge
/// (a, b) where the cut crosses it, asked only for corners of opposite sides.
/// Sub-simplices of zero measure (a corner on the cut) are left out.
CellFragments cell_fragments(int dimension, const std::array<Vec3, 4>& corners, const std::array<int, 4>& sides,
                             const std::function<Vec3(int, int)>& crossing);

/// Signed measure of the simplex of dim + 1 points (volume, or area in the x-y plane).
double simplex_measure(int dimension, const Vec3* points);

}  // namespace kerf
