#pragma once
// Time integration of a mechanical system (a body and its solver-side terms),
// whatever the method. A static analysis is a stepper too: its steps are load
// increments in pseudo-time 0..1.
#include <memory>
#include <span>
#include <string>

#include "core/run_report.h"
#include "solvers/mechanical_system.h"

namespace kerf {

struct SolverState {
  double t = 0.0;  // s (static: load factor)
  int step = 0;
  Vector u, v, a;  // m, m/s, m/s^2 over all dofs
};

class Stepper {
 public:
  virtual ~Stepper() = default;
  /// Sets u to the prescribed values, v = 0 and the initial acceleration.
  virtual void initialize(SolverState& state) = 0;
  virtual void advance(SolverState& state, double dt) = 0;
  virtual double kinetic_energy(const SolverState& state) const = 0;
  /// f_int(u) + M a + C v - f_ext over all dofs: the support reactions at constrained dofs (N).
  virtual Vector reaction(const SolverState& state) = 0;
  /// The external force the scheme applies at this state (N): f_ext(t), or in a
  /// static run f_ext scaled by the load factor.
  virtual void applied_load(const SolverState& state, Vector& f) const = 0;
  /// The body's discretization changed under the state (a cut grew; same
  /// dofs): re-reads what the scheme keeps of it (mass, stiffness, factors)
  /// and makes the state consistent again (the acceleration of explicit and
  /// Newmark schemes). u and v carry over unchanged.
  virtual void discretization_changed(SolverState& state) = 0;
  /// The loads or the prescribed values changed between steps (not which
  /// dofs are prescribed: a session's hand on a sphere or a load): a stepper
  /// that keeps them takes the new ones into the state now (central
  /// differences: u at those dofs and the acceleration); the others read
  /// them every step.
  virtual void applied_changed(SolverState&) {}
  /// Makes the state's whole vectors (u, v, a over every dof) current: a
  /// stepper that keeps them in pieces (central differences on a
  /// partitioned body) fills them only when asked, so that a step sends only
  /// ghosts' values. Collective: the same call on every rank. The other
  /// steppers' state is always current.
  virtual void complete_state(SolverState&) {}
  /// The same for u alone at `dofs` (ascending; the same list on every
  /// rank): what displacement probes read.
  virtual void complete_displacement_at(SolverState&, std::span<const Index> /*dofs*/) {}
  /// Linear solves Newton made in the last step (0 for explicit).
  virtual int last_iterations() const { return 0; }
  /// The time step the run uses (s); static: 1 / load_steps.
  virtual double time_step() const = 0;
  virtual int step_count() const = 0;
  /// The fastest vibration mode the last critical-step estimate found, over
  /// all dofs (explicit schemes; empty for the others): a body that replaces
  /// this one (a cut grew) carries it over like a displacement, and the next
  /// stepper's estimate starts from it.
  virtual Vector vibration_mode() const { return {}; }
};

/// What a stepper needs of a scene, and nothing else: the solve options, the
/// material's Rayleigh damping (C = alpha M + beta K) and where solve.dt was
/// written (an explicit dt above the critical step is refused naming it).
struct StepperSettings {
  SolveOptions solve;
  double damping_mass = 0.0;       // alpha (1/s)
  double damping_stiffness = 0.0;  // beta (s)
  std::string dt_location;
};
StepperSettings stepper_settings(const Scene& scene);

/// Picks static, implicit Euler, Newmark or central differences from the settings.
/// Refuses an explicit dt above the critical estimate, naming the estimate.
/// With `carried_mode` (a previous stepper's vibration_mode() carried to this
/// body), the stepper continues a run whose body was replaced: an explicit one
/// estimates its critical step in discretization_changed, from that mode.
std::unique_ptr<Stepper> make_stepper(MechanicalSystem& mechanics, const StepperSettings& settings, RunReport& report,
                                      const Vector& carried_mode = {});

}  // namespace kerf
