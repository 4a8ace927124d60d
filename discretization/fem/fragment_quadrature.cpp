#include "discretization/fem/fragment_quadrature.h"

#include <Eigen/Dense>

#include "geometry/cell_fragments.h"

namespace kerf {
namespace {

/// Columns v_k - v_0 of the sub-simplex at `v` (identity beyond dim).
Eigen::Matrix3d edges(int dim, const Vec3* v) {
  Eigen::Matrix3d E = Eigen::Matrix3d::Identity();
  for (int k = 0; k < dim; ++k) E.col(k).head(dim) = (v[k + 1] - v[0]).head(dim);
  return E;
}

}  // namespace

QuadratureRule fragment_quadrature(int dim, std::span<const Vec3> fragment, const QuadratureRule& reference) {
  QuadratureRule out;
  const std::size_t corners = static_cast<std::size_t>(dim) + 1;
  for (std::size_t s = 0; s < fragment.size(); s += corners) {
    const Eigen::Matrix3d E = edges(dim, &fragment[s]);
    const double scale = std::abs(E.determinant());
    for (std::size_t q = 0; q < reference.points.size(); ++q) {
      out.points.push_back(fragment[s] + E * reference.points[q]);
      out.weights.push_back(reference.weights[q] * scale);
    }
  }
  return out;
}

double fragment_measure(int dim, std::span<const Vec3> fragment) {
  double sum = 0.0;
  for (std::size_t s = 0; s < fragment.size(); s += dim + 1) sum += simplex_measure(dim, &fragment[s]);
  return sum;
}

bool fragment_holds(int dim, std::span<const Vec3> fragment, const Vec3& xi, double tolerance) {
  for (std::size_t s = 0; s < fragment.size(); s += dim + 1) {
    const Vec3 local = edges(dim, &fragment[s]).inverse() * (xi - fragment[s]);
    double rest = 1.0;
    bool inside = true;
    for (int k = 0; k < dim; ++k) {
      inside &= local[k] >= -tolerance;
      rest -= local[k];
    }
    if (inside && rest >= -tolerance) return true;
  }
  return false;
}

}  // namespace kerf
