#include "studies/study_hertz_problem.h"

#include <cmath>

#include "studies/study_scenes.h"

namespace kerf::hertz {

double indentation() { return contact_radius * contact_radius / sphere_radius; }

double force() {
  const double e_star = young / (1.0 - poisson * poisson);
  return 4.0 / 3.0 * e_star * std::sqrt(sphere_radius) * std::pow(indentation(), 1.5);
}

Scene scene(const MethodChoice& d, double block, double coarse, const std::vector<RefineRegion>& refine) {
  using namespace study_scene;
  Scene scene = box_body("hertz", Vec3(0, 0, 0), Vec3(block, block, block));
  scene.material = material(MaterialModel::linear, young, poisson);
  DiscretizationOptions& discretization = scene.discretization;
  discretization.method = d.method;
  discretization.fem.element = d.element;
  discretization.fem.size = coarse;
  discretization.meshless.spacing = coarse;
  discretization.meshless.gradient = d.gradient;
  discretization.refine = refine;
  scene.boundary = {held(0, 0.0, {true, false, false}), held(1, 0.0, {false, true, false}), held(2, 0.0)};
  ContactSphere sphere;
  sphere.center = Vec3(0, 0, block + sphere_radius);
  sphere.radius = sphere_radius;
  sphere.force = Vec3(0, 0, -force() / 4.0);
  scene.contact = {sphere};
  scene.output.probes = {contact_probe("indent", 0, ProbeField::indentation),
                         contact_probe("push", 0, ProbeField::contact_force)};
  return scene;
}

Scene graded_scene(const MethodChoice& d, int n) {
  const double h = contact_radius / n;
  std::vector<RefineRegion> refine;
  for (int k = 0; k < graded_levels; ++k) {
    const double edge = finest_box * std::ldexp(1.0, k);
    refine.push_back({Box{Vec3(0, 0, study_scene::as_written(graded_block - edge)), Vec3(edge, edge, graded_block)},
                      h * std::ldexp(1.0, k)});
  }
  return scene(d, graded_block, h * std::ldexp(1.0, graded_levels), refine);
}

}  // namespace kerf::hertz
