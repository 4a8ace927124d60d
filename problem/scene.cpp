#include "problem/scene.h"

namespace kerf {

bool Box::contains(const Vec3& p, double tolerance) const {
  for (int i = 0; i < 3; ++i)
    if (p[i] < min[i] - tolerance || p[i] > max[i] + tolerance) return false;
  return true;
}

bool BoundaryCondition::is_dirichlet() const {
  for (int i = 0; i < 3; ++i)
    if (fixed[i] || displacement[i]) return true;
  return false;
}

}  // namespace kerf
