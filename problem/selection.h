#pragma once
// Which points of a discretization a scene selection takes (shared by every method).
#include <span>
#include <vector>

#include "problem/scene.h"

namespace kerf {

/// plane: boundary points within 1e-9 * domain_size of the plane; box: boundary
/// points inside the closed box; point: the one point nearest to it.
/// Throws, naming the selection's scene line, when it takes nothing.
std::vector<Index> select_points(const Selection& selection, std::span<const Vec3> points,
                                 std::span<const char> on_boundary, double domain_size);

}  // namespace kerf
