#pragma once
// Distance from a point to a set of straight boundary facets: triangles in 3D,
// segments in 2D (stored as triangles whose last two corners coincide).
#include <array>
#include <span>

#include "core/types.h"

namespace kerf {

/// The smallest distance (m) from x to the facets; infinity when there are none.
double distance_to_facets(const Vec3& x, std::span<const std::array<Vec3, 3>> facets);

}  // namespace kerf
