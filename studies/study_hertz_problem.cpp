#include "studies/study_hertz_problem.h"

#include <cmath>
#include <sstream>

namespace kerf::hertz {

double indentation() { return contact_radius * contact_radius / sphere_radius; }

double force() {
  const double e_star = young / (1.0 - poisson * poisson);
  return 4.0 / 3.0 * e_star * std::sqrt(sphere_radius) * std::pow(indentation(), 1.5);
}

std::string scene(const MethodChoice& d, double block, double coarse, const std::string& refine) {
  std::ostringstream s;
  s.precision(12);
  s << "name: hertz\n"
    << "domain: {box: {min: [0, 0, 0], max: [" << block << ", " << block << ", " << block << "]}}\n"
    << "material: {model: linear, young: " << young << ", poisson: " << poisson << "}\n"
    << "discretization:\n"
    << "  method: " << d.method << "\n"
    << "  fem: {element: " << d.element << ", size: " << coarse << "}\n"
    << "  meshless: {spacing: " << coarse << ", gradient: " << d.gradient << "}\n"
    << "  refine:" << (refine.empty() ? " []\n" : "\n" + refine)
    << "boundary:\n"
    << "  - {select: {plane: {axis: x, at: 0}}, fix: [x]}\n"
    << "  - {select: {plane: {axis: y, at: 0}}, fix: [y]}\n"
    << "  - {select: {plane: {axis: z, at: 0}}, fix: [x, y, z]}\n"
    << "contact:\n"
    << "  - sphere: {center: [0, 0, " << block + sphere_radius << "], radius: " << sphere_radius << "}\n"
    << "    force: [0, 0, " << -force() / 4.0 << "]\n"
    << "solve: {analysis: static}\n"
    << "output:\n"
    << "  vtk: false\n"
    << "  probes:\n"
    << "    - {name: indent, contact: 0, field: indentation}\n"
    << "    - {name: push, contact: 0, field: contact_force}\n";
  return s.str();
}

std::string graded_scene(const MethodChoice& d, int n) {
  const double h = contact_radius / n;
  std::ostringstream refine;
  refine.precision(12);
  for (int k = 0; k < graded_levels; ++k) {
    const double edge = finest_box * std::ldexp(1.0, k);
    refine << "    - {box: {min: [0, 0, " << graded_block - edge << "], max: [" << edge << ", " << edge << ", "
           << graded_block << "]}, size: " << h * std::ldexp(1.0, k) << "}\n";
  }
  return scene(d, graded_block, h * std::ldexp(1.0, graded_levels), refine.str());
}

}  // namespace kerf::hertz
