#include "geometry/point_location.h"

#include <Eigen/Dense>
#include <limits>

namespace kerf {

std::optional<CellPoint> locate_point(const Mesh& mesh, const Vec3& x, double distance) {
  const int dim = mesh.dimension;
  CellPoint best;
  double best_outside = std::numeric_limits<double>::infinity();
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    auto n = mesh.cell(c);
    const Vec3& x0 = mesh.nodes[n[0]];
    Mat3 J = Mat3::Identity();
    for (int k = 0; k < dim; ++k) J.col(k) = mesh.nodes[n[k + 1]] - x0;
    Vec3 local = J.inverse() * (x - x0);
    if (dim == 2) local.z() = 0.0;
    // How far outside the reference simplex, measured in physical length.
    Vec3 clamped = local.cwiseMax(0.0);
    double sum = clamped.head(dim).sum();
    if (sum > 1.0) clamped.head(dim) /= sum;
    double outside = (J * (clamped - local)).norm();
    if (outside < best_outside) {
      best_outside = outside;
      best.cell = c;
      best.local = outside > 0.0 ? clamped : local;
    }
    if (outside == 0.0) break;
  }
  if (best.cell < 0 || best_outside > distance) return std::nullopt;
  return best;
}

}  // namespace kerf
