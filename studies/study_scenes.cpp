#include "studies/study_scenes.h"

#include <cstdio>
#include <cstdlib>

namespace kerf::study_scene {

double as_written(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.12g", x);
  return std::strtod(text, nullptr);
}

Scene box_body(const std::string& name, const Vec3& min, const Vec3& max) {
  Scene scene;
  scene.name = name;
  scene.box = Box{min, max};
  scene.output.dir = "results/" + name;
  scene.output.vtk_every = 0;
  return scene;
}

Material material(MaterialModel model, double young, double poisson, double density, double damping_mass) {
  Material m;
  m.model = model;
  m.young = young;
  m.poisson = poisson;
  m.density = density;
  m.damping_mass = damping_mass;
  return m;
}

Selection plane(int axis, double at) {
  Selection s;
  s.kind = Selection::Kind::plane;
  s.axis = axis;
  s.at = at;
  return s;
}

BoundaryCondition held(int axis, double at, std::array<bool, 3> fixed) {
  BoundaryCondition bc;
  bc.select = plane(axis, at);
  bc.fixed = fixed;
  return bc;
}

Probe displacement_probe(const std::string& name, const Vec3& point) {
  Probe p;
  p.name = name;
  p.field = ProbeField::displacement;
  p.point = point;
  return p;
}

Probe reaction_probe(const std::string& name, const Selection& where) {
  Probe p;
  p.name = name;
  p.field = ProbeField::reaction;
  p.select = where;
  return p;
}

Probe energy_probe(const std::string& name) {
  Probe p;
  p.name = name;
  p.field = ProbeField::energy;
  return p;
}

Probe contact_probe(const std::string& name, int contact, ProbeField field) {
  Probe p;
  p.name = name;
  p.field = field;
  p.contact = contact;
  return p;
}

SolveOptions explicit_unstable_steps(double dt, int steps) {
  SolveOptions solve = implicit_steps(dt, steps);
  solve.integrator = Integrator::central_difference;
  solve.newton = NewtonOptions{};
  solve.allow_unstable_dt = true;
  return solve;
}

SolveOptions implicit_steps(double dt, int steps) {
  SolveOptions solve;
  solve.analysis = Analysis::dynamic;
  solve.integrator = Integrator::implicit_euler;
  solve.dt = dt;
  solve.duration = dt * steps;
  solve.newton.max_iterations = 1;
  return solve;
}

Scene implicit_cube(const std::string& name, double size, int steps, LinearSolverKind solver, const std::string& petsc,
                    const std::string& probe) {
  Scene scene = box_body(name, Vec3(0, 0, 0), Vec3(0.1, 0.1, 0.1));
  scene.material = material(MaterialModel::corotational, 3000.0, 0.3, 1000.0, 4.0);
  scene.discretization.fem.size = size;
  scene.boundary = {held(2, 0.0)};
  scene.gravity = Vec3(0, 0, -9.81);
  scene.solve = implicit_steps(0.01, steps);
  scene.solve.linear_solver = solver;
  if (!petsc.empty()) {
    scene.solve.petsc = petsc;
    scene.solve.petsc_written = true;
  }
  scene.solve.linear_tolerance = 1.0e-8;
  scene.output.probes = {displacement_probe(probe, Vec3(0.05, 0.05, 0.1))};
  return scene;
}

}  // namespace kerf::study_scene
