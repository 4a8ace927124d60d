#pragma once
// Which cell of a mesh holds a point, and where inside it.
#include <optional>

#include "geometry/mesh.h"

namespace kerf {

struct CellPoint {
  Index cell = -1;
  Vec3 local = Vec3::Zero();  // reference coordinates (xi, eta, zeta) of the straight-sided cell
};

/// The cell holding x (within `tolerance` in reference coordinates), or the one
/// nearest to it when x lies within `distance` (m) of the mesh; nullopt otherwise.
std::optional<CellPoint> locate_point(const Mesh& mesh, const Vec3& x, double distance);

}  // namespace kerf
