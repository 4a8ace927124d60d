#include "solvers/implicit_steppers.h"

#include <cmath>
#include <sstream>

#include "core/check.h"
#include "solvers/implicit_system.h"
#include "solvers/increment_control.h"
#include "solvers/newton.h"

namespace kerf {
namespace {

std::string step_name(const char* what, int step, double t) {
  std::ostringstream s;
  s << what << " step " << step << " (t = " << t << " s)";
  return s.str();
}

void apply_dirichlet(const std::vector<DirichletDof>& prescribed, Vector& u) {
  for (const DirichletDof& d : prescribed) u[d.dof] = d.value;
}

class StaticStepper final : public Stepper {
 public:
  StaticStepper(MechanicalSystem& mechanics, const SolveOptions& solve, RunReport& report)
      : mechanics_(mechanics),
        options_(solve),
        system_(mechanics, solve, false, report),
        report_(report),
        control_(1.0 / solve.load_steps, solve, report) {
    load_at(1.0, f_ext_);
    load_scale_ = f_ext_.norm();
  }

  void initialize(SolverState& s) override {
    s.u = Vector::Zero(mechanics_.dof_count());
    s.v = Vector::Zero(mechanics_.dof_count());
    s.a = Vector::Zero(mechanics_.dof_count());
  }

  void advance(SolverState& s, double) override {
    // From the step count, so the last step is exactly the full load; the
    // increments between are the control's.
    const double target = std::min(1.0, static_cast<double>(s.step + 1) / options_.load_steps);
    iterations_ = 0;
    while (s.t < target) {
      const double load = control_.next(s.t, target).end;
      std::ostringstream where;
      where << "static load step " << s.step + 1 << " (load factor " << load << ")";
      const Vector start = s.u;
      std::optional<ContactTerm::AugmentationState> contact_start;
      if (const ContactTerm* contact = mechanics_.contact()) contact_start = contact->augmentation_state();
      const NewtonResult result = solve_at(load, s.u, where.str());
      iterations_ += result.iterations;
      if (result.converged()) {
        control_.accepted(load - s.t, result);
        s.t = load;
        continue;
      }
      // The tangent at the last equilibrium does not depend on the load: a
      // smaller increment cannot make it factorizable.
      if (result.status == NewtonStatus::factorization_failed && result.iterations == 0)
        throw SharedFailure(result.failure);
      s.u = start;
      if (contact_start) mechanics_.contact()->restore(*contact_start);
      control_.rejected(s.t, load, describe(result, options_.newton), where.str());
    }
    ++s.step;
  }

  void discretization_changed(SolverState&) override { system_.discretization_changed(); }
  double kinetic_energy(const SolverState&) const override { return 0.0; }
  Vector reaction(const SolverState& s) override {
    Vector r;
    system_.internal_force(s.u, r, false);
    applied_load(s, f_ext_);
    return r - f_ext_;
  }
  void applied_load(const SolverState& s, Vector& f) const override { load_at(s.t, f); }
  int last_iterations() const override { return iterations_; }
  double time_step() const override { return 1.0 / options_.load_steps; }
  int step_count() const override { return options_.load_steps; }

 private:
  /// The dead loads scaled by the load factor (pseudo-time of the static run).
  void load_at(double factor, Vector& f) const {
    mechanics_.external_force(factor, f);
    f *= factor;
  }

  /// Equilibrium at load factor `load` from u (Newton, then augmented
  /// Lagrangian rounds while contact is still off): how the last solve ended.
  NewtonResult solve_at(double load, Vector& u, const std::string& where) {
    load_at(load, f_ext_);
    std::vector<DirichletDof> prescribed;
    auto read_prescribed = [&] {
      prescribed = mechanics_.dirichlet(load);
      for (DirichletDof& d : prescribed)
        if (d.scales_with_load) d.value *= load;
    };
    read_prescribed();
    auto residual = [&](const Vector& x, Vector& r, bool tangent) {
      system_.internal_force(x, r, tangent);
      r -= f_ext_;
      if (tangent) system_.update_matrix(0.0, 1.0, where);
    };
    auto solve = [&] {
      NewtonResult result =
          newton_solve(system_, options_.newton, residual, {f_ext_.norm(), load_scale_}, prescribed, u, where);
      load_scale_ = std::max(load_scale_, result.reference);  // a displacement-driven run's: its first residual
      return result;
    };
    NewtonResult result = solve();
    // Contact: augmented Lagrangian rounds until no point penetrates beyond
    // tolerance and force-driven spheres carry their force.
    int round = 0;
    for (ContactTerm* contact = mechanics_.contact(); result.converged() && contact && contact->augment(u, load);
         ++round) {
      KERF_CHECK_SHARED(round < max_augmentations, where, ": contact did not settle in ", max_augmentations,
                        " augmented Lagrangian rounds (penetration or the sphere's force still off); "
                        "try more load steps");
      read_prescribed();
      const int before = result.iterations;
      result = solve();
      result.iterations += before;
    }
    if (round > 0) report_.solver.contact_augmentations += round;
    return result;
  }

  static constexpr int max_augmentations = 50;
  MechanicalSystem& mechanics_;
  SolveOptions options_;
  ImplicitSystem system_;
  RunReport& report_;
  IncrementControl control_;
  Vector f_ext_;
  double load_scale_ = 0.0;  // N: the full load's norm, or the largest first residual
  int iterations_ = 0;       // over the increments of the last step
};

/// One-step implicit dynamics: each scheme supplies a(u), v(u) and the
/// coefficients of dr/du; the residual M (a + alpha v) + beta K v + f_int - f_ext,
/// the Newton loop and the reactions are shared.
class DynamicImplicitStepper : public Stepper {
 public:
  DynamicImplicitStepper(MechanicalSystem& mechanics, const StepperSettings& settings, RunReport& report)
      : mechanics_(mechanics),
        options_(settings.solve),
        alpha_(settings.damping_mass),
        beta_(settings.damping_stiffness),
        system_(mechanics, settings.solve, true, report),
        control_(settings.solve.dt, settings.solve, report) {}

  void initialize(SolverState& s) override {
    const Index n = mechanics_.dof_count();
    s.u = Vector::Zero(n);
    s.v = Vector::Zero(n);
    apply_dirichlet(mechanics_.dirichlet(0.0), s.u);
    s.a = uses_acceleration() ? initial_acceleration(s) : Vector::Zero(n);
  }

  void advance(SolverState& s, double dt) override {
    // The step ends at t + dt whatever substeps the control takes on the way.
    const double end = s.t + dt;
    iterations_ = 0;
    while (s.t < end) {
      const auto [t1, step] = control_.next(s.t, end);
      const std::string where = step_name(name(), s.step + 1, t1);
      const NewtonResult result = attempt(s, t1, step, where);
      iterations_ += result.iterations;
      if (result.converged()) {
        control_.accepted(step, result);
        s.t = t1;
        continue;
      }
      control_.rejected(s.t, t1, describe(result, options_.newton), where);
    }
    ++s.step;
  }

  /// One implicit step of length dt from s to t1: s (but its time) updated
  /// when Newton converged, untouched otherwise.
  NewtonResult attempt(SolverState& s, double t1, double dt, const std::string& where) {
    mechanics_.external_force(t1, f_ext_);
    load_scale_ = std::max(load_scale_, f_ext_.norm());
    mechanics_.begin_time_step(s.u);
    Vector u = s.u;
    Vector a, v;
    auto residual = [&](const Vector& x, Vector& r, bool tangent) {
      system_.internal_force(x, r, tangent);
      kinematics(s, dt, x, a, v);
      r += system_.mass_times(a + alpha_ * v) - f_ext_;
      if (beta_ != 0.0) r += beta_ * system_.stiffness_times(v);
      if (tangent) {
        auto [cm, ck] = matrix_coefficients(dt);
        system_.update_matrix(cm, ck, where);
      }
    };
    const NewtonResult result = newton_solve(system_, options_.newton, residual, {f_ext_.norm(), load_scale_},
                                             mechanics_.dirichlet(t1), u, where);
    load_scale_ = std::max(load_scale_, result.reference);
    if (!result.converged()) return result;
    kinematics(s, dt, u, a, v);
    s.u = std::move(u);
    s.v = std::move(v);
    s.a = std::move(a);
    return result;
  }

  void discretization_changed(SolverState& s) override {
    system_.discretization_changed();
    if (uses_acceleration()) s.a = initial_acceleration(s);
  }
  double kinetic_energy(const SolverState& s) const override { return 0.5 * s.v.dot(system_.mass_times(s.v)); }
  Vector reaction(const SolverState& s) override {
    Vector r;
    system_.internal_force(s.u, r, false);
    mechanics_.external_force(s.t, f_ext_);
    r += system_.mass_times(s.a + alpha_ * s.v) - f_ext_;
    if (beta_ != 0.0) r += beta_ * system_.stiffness_times(s.v);
    return r;
  }
  void applied_load(const SolverState& s, Vector& f) const override { mechanics_.external_force(s.t, f); }
  int last_iterations() const override { return iterations_; }
  double time_step() const override { return options_.dt; }
  int step_count() const override {
    return std::max(1, static_cast<int>(std::llround(options_.duration / options_.dt)));
  }

 protected:
  virtual const char* name() const = 0;
  /// a(u) and v(u) of the scheme from the state at the start of the step.
  virtual void kinematics(const SolverState& s, double dt, const Vector& u, Vector& a, Vector& v) const = 0;
  /// dr/du = c_M M + c_K K.
  virtual std::pair<double, double> matrix_coefficients(double dt) const = 0;
  /// Whether a(u) depends on the previous acceleration (then a0 is solved for).
  virtual bool uses_acceleration() const = 0;

  /// M a = f_ext(t) - f_int(u) - C v on the free dofs (zero at constrained dofs).
  Vector initial_acceleration(const SolverState& s) {
    Vector f_int;
    system_.internal_force(s.u, f_int, true);
    mechanics_.external_force(s.t, f_ext_);
    Vector rhs = f_ext_ - f_int - alpha_ * system_.mass_times(s.v);
    if (beta_ != 0.0) rhs -= beta_ * system_.stiffness_times(s.v);
    system_.update_matrix(1.0, 0.0, std::string(name()) + " initial acceleration");
    Vector a = Vector::Zero(mechanics_.dof_count());
    system_.free().add_to_full(system_.solve(system_.free().restrict_vector(rhs), "initial acceleration"), a);
    return a;
  }

  MechanicalSystem& mechanics_;
  SolveOptions options_;
  double alpha_, beta_;  // Rayleigh damping C = alpha M + beta K
  ImplicitSystem system_;
  IncrementControl control_;
  Vector f_ext_;
  double load_scale_ = 0.0;  // N: the largest external load or first residual so far
  int iterations_ = 0;       // over the substeps of the last step
};

class ImplicitEulerStepper final : public DynamicImplicitStepper {
 public:
  using DynamicImplicitStepper::DynamicImplicitStepper;

 protected:
  const char* name() const override { return "implicit Euler"; }
  bool uses_acceleration() const override { return false; }
  void kinematics(const SolverState& s, double dt, const Vector& u, Vector& a, Vector& v) const override {
    v = (u - s.u) / dt;
    a = (v - s.v) / dt;
  }
  std::pair<double, double> matrix_coefficients(double dt) const override {
    return {1.0 / (dt * dt) + alpha_ / dt, 1.0 + beta_ / dt};
  }
};

class NewmarkStepper final : public DynamicImplicitStepper {
 public:
  using DynamicImplicitStepper::DynamicImplicitStepper;

 protected:
  const char* name() const override { return "Newmark"; }
  bool uses_acceleration() const override { return true; }
  // Average acceleration: beta = 1/4, gamma = 1/2.
  void kinematics(const SolverState& s, double dt, const Vector& u, Vector& a, Vector& v) const override {
    a = 4.0 / (dt * dt) * (u - s.u - dt * s.v) - s.a;
    v = s.v + 0.5 * dt * (s.a + a);
  }
  std::pair<double, double> matrix_coefficients(double dt) const override {
    return {4.0 / (dt * dt) + 2.0 * alpha_ / dt, 1.0 + 2.0 * beta_ / dt};
  }
};

}  // namespace

std::unique_ptr<Stepper> make_static_stepper(MechanicalSystem& mechanics, const SolveOptions& solve,
                                             RunReport& report) {
  return std::make_unique<StaticStepper>(mechanics, solve, report);
}
std::unique_ptr<Stepper> make_implicit_euler_stepper(MechanicalSystem& mechanics, const StepperSettings& settings,
                                                     RunReport& report) {
  return std::make_unique<ImplicitEulerStepper>(mechanics, settings, report);
}
std::unique_ptr<Stepper> make_newmark_stepper(MechanicalSystem& mechanics, const StepperSettings& settings,
                                              RunReport& report) {
  return std::make_unique<NewmarkStepper>(mechanics, settings, report);
}

}  // namespace kerf
