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

const char* to_string(MaterialModel m) {
  static const char* names[] = {"linear", "corotational", "stvk", "neohookean"};
  return names[static_cast<int>(m)];
}
const char* to_string(Method m) {
  static const char* names[] = {"fem", "efg", "nodal"};
  return names[static_cast<int>(m)];
}
const char* to_string(ElementType e) {
  static const char* names[] = {"tet4", "tet10", "tri3", "tri6"};
  return names[static_cast<int>(e)];
}
const char* to_string(Integrator i) {
  static const char* names[] = {"implicit-euler", "newmark", "central-difference"};
  return names[static_cast<int>(i)];
}
const char* to_string(LinearSolverKind k) {
  static const char* names[] = {"cholmod", "petsc", "cg", "ldlt"};
  return names[static_cast<int>(k)];
}

}  // namespace kerf
