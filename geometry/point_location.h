#pragma once
// Which cell of a mesh holds a point, and where inside it.
#include <array>
#include <optional>
#include <vector>

#include "geometry/mesh.h"

namespace kerf {

struct CellPoint {
  Index cell = -1;
  Vec3 local = Vec3::Zero();  // reference coordinates (xi, eta, zeta) of the straight-sided cell
};

/// The cell holding x (within `tolerance` in reference coordinates), or the one
/// nearest to it when x lies within `distance` (m) of the mesh; nullopt otherwise.
/// Looks at every cell: for one point. Many points: CellLocator.
std::optional<CellPoint> locate_point(const Mesh& mesh, const Vec3& x, double distance);

/// The same answers as locate_point (the lowest-numbered cell holding x), from
/// a uniform grid of bins over the cells' bounding boxes: a point inside the
/// mesh looks at the cells of its bin only.
class CellLocator {
 public:
  explicit CellLocator(const Mesh& mesh);
  /// `mesh` must be the one the locator was built on.
  std::optional<CellPoint> locate(const Mesh& mesh, const Vec3& x, double distance) const;

 private:
  Index bin_of(const Vec3& x) const;  // -1 outside the grid
  Vec3 origin_ = Vec3::Zero();
  double bin_size_ = 1.0;
  std::array<Index, 3> bins_{1, 1, 1};
  std::vector<Index> start_;  // bins + 1 offsets into cells_
  std::vector<Index> cells_;  // per bin, increasing
};

}  // namespace kerf
