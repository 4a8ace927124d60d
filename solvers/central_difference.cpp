#include "solvers/central_difference.h"

#include <cmath>
#include <sstream>

#include "core/check.h"
#include "discretization/body_capabilities.h"
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
  CentralDifferenceStepper(MechanicalSystem& mechanics, const Scene& scene, RunReport& report)
      : mechanics_(mechanics), report_(report), options_(scene.solve), alpha_(scene.material.damping_mass),
        beta_(scene.material.damping_stiffness), constrained_(mechanics.dirichlet(0.0)) {
    ScopedTimer timer(report.phases, Phase::setup);
    report.add_stage("mass");
    mass_ = mechanics_.lumped_mass();
    KERF_CHECK((mass_.array() > 0.0).all(), "the lumped mass has a zero or negative entry: central differences need a "
               "positive diagonal mass");
    inverse_mass_ = mass_.cwiseInverse();
    critical_step_ = estimate_critical_step();
    if (options_.dt > critical_step_ && !options_.allow_unstable_dt) {
      std::ostringstream why;
      why << scene.locate("solve.dt").describe() << ": value " << options_.dt
          << " s is above the critical time step of central differences for this discretization and material, "
          << critical_step_ << " s (2 / omega_max by Lanczos" << (beta_ > 0 ? ", with stiffness damping" : "")
          << "); expected dt <= " << critical_step_ << " s, or an implicit integrator (or solve.allow_unstable_dt: true to "
          << "run it anyway)";
      throw Error(why.str());
    }
  }

  void initialize(SolverState& s) override {
    const Index n = mechanics_.dof_count();
    s.u = Vector::Zero(n);
    s.v = Vector::Zero(n);
    for (const DirichletDof& d : constrained_) s.u[d.dof] = d.value;
    mechanics_.external_force(0.0, f_ext_);
    mechanics_.internal_force(s.u, f_int_);
    acceleration(s.v, s.a);
  }

  void advance(SolverState& s, double dt) override {
    const double t1 = s.t + dt;
    half_velocity_ = s.v + 0.5 * dt * s.a;
    zero_constrained(half_velocity_);
    s.u += dt * half_velocity_;
    mechanics_.external_force(t1, f_ext_);
    // f_int(u + beta v) = f_int(u) + beta K v to first order: stiffness damping in one evaluation.
    {
      ScopedTimer timer(report_.phases, Phase::assembly);  // the explicit step's phase studies compare
      if (beta_ != 0.0) {
        damped_u_ = s.u + beta_ * half_velocity_;
        mechanics_.internal_force(damped_u_, f_int_);
      } else {
        mechanics_.internal_force(s.u, f_int_);
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
    mass_ = mechanics_.lumped_mass();
    inverse_mass_ = mass_.cwiseInverse();
    // A remeshed body comes with a new stepper, which has read no load yet.
    mechanics_.external_force(s.t, f_ext_);
    if (beta_ != 0.0) {
      damped_u_ = s.u + beta_ * s.v;
      mechanics_.internal_force(damped_u_, f_int_);
    } else {
      mechanics_.internal_force(s.u, f_int_);
    }
    acceleration(s.v, s.a);
  }

  double kinetic_energy(const SolverState& s) const override { return 0.5 * s.v.dot(mass_.cwiseProduct(s.v)); }
  Vector reaction(const SolverState& s) override {
    Vector r;
    mechanics_.internal_force(s.u, r);
    mechanics_.external_force(s.t, f_ext_);
    return r + mass_.cwiseProduct(s.a + alpha_ * s.v) - f_ext_;
  }
  void applied_load(const SolverState& s, Vector& f) const override { mechanics_.external_force(s.t, f); }
  double time_step() const override { return options_.dt; }
  int step_count() const override {
    return std::max(1, static_cast<int>(std::llround(options_.duration / options_.dt)));
  }

 private:
  /// The stable step with the lumped mass (s): the larger of the element bound
  /// (FEM; safe but often twice too small) and 2 / omega_max by Lanczos on the
  /// assembled stiffness at rest (an upper bound on omega_max), with stiffness damping.
  double estimate_critical_step() {
    // A partitioned body's bound and stiffness are over its own cells: the ranks' parts are combined.
    const RankSum* ranks = mechanics_.rank_sum();
    std::optional<double> element_bound;
    if (const auto* bound = capability<ElementStepBound>(mechanics_.body()))
      element_bound = ranks ? ranks->smallest(bound->critical_time_step()) : bound->critical_time_step();
    report_.add_stage("stiffness");
    SparseMatrix K = build_pattern(mechanics_);
    mechanics_.tangent_into(Vector::Zero(mechanics_.dof_count()), K, nullptr);
    auto stiffness_times = [&](const Vector& x, Vector& y) {
      y = K * x;
      if (ranks) ranks->sum(y);
    };
    const EigenvalueBound omega2 =
        largest_eigenvalue(stiffness_times, mass_, FreeDofs(mechanics_.dof_count(), constrained_));
    const double lanczos_step = 2.0 / std::sqrt(omega2.upper_bound);
    const double step = damped_critical_step(std::max(lanczos_step, element_bound.value_or(0.0)), beta_);
    report_.solver.critical_dt_s = step;
    if (element_bound) report_.solver.critical_dt_element_bound_s = damped_critical_step(*element_bound, beta_);
    return step;
  }

  /// a = M^-1 (f_ext - f_int - alpha M v), zero at constrained dofs; no allocation once sized.
  void acceleration(const Vector& v, Vector& a) const {
    a = inverse_mass_.cwiseProduct(f_ext_ - f_int_) - alpha_ * v;
    zero_constrained(a);
  }
  void zero_constrained(Vector& x) const {
    for (const DirichletDof& d : constrained_) x[d.dof] = 0.0;
  }

  const MechanicalSystem& mechanics_;
  RunReport& report_;
  SolveOptions options_;
  double alpha_, beta_;
  std::vector<DirichletDof> constrained_;
  Vector mass_, inverse_mass_, f_ext_, f_int_, half_velocity_, damped_u_;
  double critical_step_ = 0.0;
};

}  // namespace

std::unique_ptr<Stepper> make_central_difference_stepper(MechanicalSystem& mechanics, const Scene& scene,
                                                         RunReport& report) {
  return std::make_unique<CentralDifferenceStepper>(mechanics, scene, report);
}

}  // namespace kerf
