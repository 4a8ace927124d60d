#include "solvers/central_difference.h"

#include <cmath>
#include <sstream>

#include "core/check.h"
#include "solvers/largest_eigenvalue.h"
#include "solvers/sparse_assembly.h"

namespace kerf {

double damped_critical_step(double undamped_step, double beta) {
  double omega = 2.0 / undamped_step;
  double xi = 0.5 * beta * omega;
  return undamped_step * (std::sqrt(1.0 + xi * xi) - xi);
}

namespace {

class CentralDifferenceStepper final : public Stepper {
 public:
  CentralDifferenceStepper(DiscreteBody& body, const Scene& scene, RunReport& report)
      : body_(body), report_(report), options_(scene.solve), alpha_(scene.material.damping_mass),
        beta_(scene.material.damping_stiffness), constrained_(body.dirichlet(0.0)) {
    ScopedTimer timer(report.phases, Phase::setup);
    report.add_stage("mass");
    mass_ = body_.lumped_mass();
    KERF_CHECK((mass_.array() > 0.0).all(), "the lumped mass has a zero or negative entry: central differences need a "
               "positive diagonal mass");
    inverse_mass_ = mass_.cwiseInverse();
    // The element bound (FEM) is safe but often twice too small; Lanczos on
    // the assembled stiffness at rest finds omega_max itself (an upper bound on it).
    const std::optional<double> element_bound_step = body_.critical_time_step();
    report.add_stage("stiffness");
    SparseMatrix K = build_pattern(body_);
    body_.tangent(Vector::Zero(body_.dof_count()), add_into(K), nullptr);
    EigenvalueBound omega2 = largest_eigenvalue(K, mass_, FreeDofs(body_.dof_count(), constrained_));
    const double lanczos_step = 2.0 / std::sqrt(omega2.upper_bound);
    critical_step_ = damped_critical_step(std::max(lanczos_step, element_bound_step.value_or(0.0)), beta_);
    report.solver.critical_dt_s = critical_step_;
    if (element_bound_step)
      report.solver.critical_dt_element_bound_s = damped_critical_step(*element_bound_step, beta_);
    if (options_.dt > critical_step_ && !options_.allow_unstable_dt) {
      std::ostringstream why;
      why << scene.file << ": key 'solve.dt': value " << options_.dt
          << " s is above the critical time step of central differences for this discretization and material, "
          << critical_step_ << " s (2 / omega_max by Lanczos" << (beta_ > 0 ? ", with stiffness damping" : "")
          << "); expected dt <= " << critical_step_ << " s, or an implicit integrator (or solve.allow_unstable_dt: true to "
          << "run it anyway)";
      throw Error(why.str());
    }
  }

  void initialize(SolverState& s) override {
    const Index n = body_.dof_count();
    s.u = Vector::Zero(n);
    s.v = Vector::Zero(n);
    for (const DirichletDof& d : constrained_) s.u[d.dof] = d.value;
    body_.external_force(0.0, f_ext_);
    body_.internal_force(s.u, f_int_);
    acceleration(s.v, s.a);
  }

  void advance(SolverState& s, double dt) override {
    const double t1 = s.t + dt;
    half_velocity_ = s.v + 0.5 * dt * s.a;
    zero_constrained(half_velocity_);
    s.u += dt * half_velocity_;
    body_.external_force(t1, f_ext_);
    // f_int(u + beta v) = f_int(u) + beta K v to first order: stiffness damping in one evaluation.
    {
      ScopedTimer timer(report_.phases, Phase::assembly);  // the explicit step's phase studies compare
      if (beta_ != 0.0) {
        damped_u_ = s.u + beta_ * half_velocity_;
        body_.internal_force(damped_u_, f_int_);
      } else {
        body_.internal_force(s.u, f_int_);
      }
    }
    acceleration(half_velocity_, s.a);
    s.v = half_velocity_ + 0.5 * dt * s.a;
    zero_constrained(s.v);
    s.t = t1;
    ++s.step;
    KERF_CHECK(s.u.allFinite(), "central-difference step ", s.step, " (t = ", t1,
               " s): the displacement became NaN or infinite: the explicit solution diverged");
  }

  void discretization_changed(SolverState& s) override {
    // The critical step is not estimated again (a Lanczos run costs an
    // assembly): the run keeps dt, and a growing instability stops it.
    mass_ = body_.lumped_mass();
    inverse_mass_ = mass_.cwiseInverse();
    if (beta_ != 0.0) {
      damped_u_ = s.u + beta_ * s.v;
      body_.internal_force(damped_u_, f_int_);
    } else {
      body_.internal_force(s.u, f_int_);
    }
    acceleration(s.v, s.a);
  }

  double kinetic_energy(const SolverState& s) const override { return 0.5 * s.v.dot(mass_.cwiseProduct(s.v)); }
  Vector reaction(const SolverState& s) override {
    Vector r;
    body_.internal_force(s.u, r);
    body_.external_force(s.t, f_ext_);
    return r + mass_.cwiseProduct(s.a + alpha_ * s.v) - f_ext_;
  }
  void applied_load(const SolverState& s, Vector& f) const override { body_.external_force(s.t, f); }
  double time_step() const override { return options_.dt; }
  int step_count() const override {
    return std::max(1, static_cast<int>(std::llround(options_.duration / options_.dt)));
  }

 private:
  /// a = M^-1 (f_ext - f_int - alpha M v), zero at constrained dofs; no allocation once sized.
  void acceleration(const Vector& v, Vector& a) const {
    a = inverse_mass_.cwiseProduct(f_ext_ - f_int_) - alpha_ * v;
    zero_constrained(a);
  }
  void zero_constrained(Vector& x) const {
    for (const DirichletDof& d : constrained_) x[d.dof] = 0.0;
  }

  const DiscreteBody& body_;
  RunReport& report_;
  SolveOptions options_;
  double alpha_, beta_;
  std::vector<DirichletDof> constrained_;
  Vector mass_, inverse_mass_, f_ext_, f_int_, half_velocity_, damped_u_;
  double critical_step_ = 0.0;
};

}  // namespace

std::unique_ptr<Stepper> make_central_difference_stepper(DiscreteBody& body, const Scene& scene,
                                                         RunReport& report) {
  return std::make_unique<CentralDifferenceStepper>(body, scene, report);
}

}  // namespace kerf
