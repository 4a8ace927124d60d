#pragma once
// The parts the studies build their scenes from, as typed Scene values: a
// box body, a material, a clamped plane, probes, and the implicit cube the
// solvers and scaling studies share. A study sets the fields it varies on
// top (scene.discretization.fem.size = h), never scene text.
#include <string>

#include "problem/scene.h"

namespace kerf::study_scene {

/// `x` to 12 significant digits, as a person writes it in a scene file. For
/// coordinates meant to fall on a lattice's nodes (a refine box's edge, a
/// blade's edge on a node row): 0.384 - 0.096 is 0.28800000000000003, and a
/// box edge an ulp off the row it was meant to hit takes another node set.
double as_written(double x);

/// A 3D scene named `name` on the box [min, max] (m), defaults elsewhere,
/// no ParaView output (studies read probes and the summary).
Scene box_body(const std::string& name, const Vec3& min, const Vec3& max);

Material material(MaterialModel model, double young, double poisson, double density = 1000.0,
                  double damping_mass = 0.0);

/// The boundary points on the plane `axis` = `at`.
Selection plane(int axis, double at);
/// The plane's points held in the components `fixed` (x, y, z).
BoundaryCondition held(int axis, double at, std::array<bool, 3> fixed = {true, true, true});

Probe displacement_probe(const std::string& name, const Vec3& point);
Probe reaction_probe(const std::string& name, const Selection& where);
Probe energy_probe(const std::string& name);
/// indentation or contact_force of the contact item `contact`.
Probe contact_probe(const std::string& name, int contact, ProbeField field);

/// Central differences, `steps` of `dt`, a dt above the critical step allowed (a stability probe looks for it).
SolveOptions explicit_unstable_steps(double dt, int steps);

/// Implicit Euler of `steps` steps of dt (s), one linearised solve a step (as SOFA does).
SolveOptions implicit_steps(double dt, int steps);

/// The solvers and scaling studies' cube: 10 cm of corotational soft tissue
/// (E = 3 kPa, nu = 0.3, mass damping 4/s) clamped at the bottom, sagging
/// under gravity, implicit Euler at 10 ms, tet4 of `size` (m), `steps`
/// steps, solved by `solver` to 1e-8 (PETSc's options `petsc` when not
/// empty); a displacement probe named `probe` at the top's centre.
Scene implicit_cube(const std::string& name, double size, int steps, LinearSolverKind solver, const std::string& petsc,
                    const std::string& probe);

}  // namespace kerf::study_scene
