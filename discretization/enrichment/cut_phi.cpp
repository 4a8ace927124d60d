#include "discretization/enrichment/cut_phi.h"

#include <cmath>

namespace kerf {

PhiValue phi_of(const CutRegion& r) {
  PhiValue phi;
  const double d2 = r.d_plus * r.d_plus + r.s * r.s;
  if (d2 == 0.0) return phi;  // on the cut: the +1 side
  const double d = std::sqrt(d2);
  phi.value = r.s / d;
  phi.front_distance = d;
  // grad (s / d) = (d+^2 grad s - s d+ grad d+) / d^3; over the cut (d+ = 0) it is 0.
  phi.gradient = (r.d_plus * r.d_plus * r.s_gradient - r.s * r.d_plus * r.d_plus_gradient) / (d2 * d);
  return phi;
}

PhiValue grid_phi(const CutSurface& cut, Index first, Index last, const CutFrame& frame, const Vec3& x) {
  return phi_of(cut_region(cut, first, last, frame, x));
}

}  // namespace kerf
