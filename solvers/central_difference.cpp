#include "solvers/central_difference.h"

#include <cmath>
#include <sstream>

#include "core/check.h"
#include "discretization/body_capabilities.h"
#include "solvers/explicit_layout.h"
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
  CentralDifferenceStepper(MechanicalSystem& mechanics, const StepperSettings& settings, RunReport& report,
                           const Vector& carried_mode)
      : mechanics_(mechanics), report_(report), options_(settings.solve), alpha_(settings.damping_mass),
        beta_(settings.damping_stiffness), constrained_(mechanics.dirichlet(0.0)),
        layout_(explicit_layout(mechanics)), layout_constrained_(layout_->constrained(constrained_)),
        dt_location_(settings.dt_location) {
    ScopedTimer timer(report.phases, Phase::setup);
    report.parallel.state_in_pieces = layout_->piece();
    report.add_stage("mass");
    mass_ = layout_->lumped_mass();
    KERF_CHECK((mass_.array() > 0.0).all(), "the lumped mass has a zero or negative entry: central differences need a "
               "positive diagonal mass");
    inverse_mass_ = mass_.cwiseInverse();
    probe_length_ = probe_length_of(mechanics_.body());
    if (carried_mode.size() == mechanics_.dof_count()) {
      // A replaced body: discretization_changed estimates, matrix-free, from
      // the carried mode, to 1e-4: a cut that adds a faster mode leaves the
      // old one's neighbourhood, and a 1% stop can end before Lanczos finds it
      // (measured on the cut study's split block: 2.42e-4 s at 1e-2 against
      // the converged 2.29e-4 s; 1e-4 gives 2.2907e-4 s in 26 ms, a cold
      // assembled estimate 68 ms).
      mode_ = FreeDofs(mechanics_.dof_count(), constrained_).restrict_vector(carried_mode);
      reestimate_tolerance_ = 1e-4;
    } else {
      critical_step_ = estimate_critical_step();
      fresh_estimate_ = true;
    }
    whole_mass_ = Vector();  // a piece layout's: built again if a reaction asks
  }

  void initialize(SolverState& s) override {
    // At the start a dt above the critical step is the scene's error; after a growth it is taken in substeps.
    if (options_.dt > critical_step_ && !options_.allow_unstable_dt) {
      std::ostringstream why;
      why << dt_location_ << ": value " << options_.dt
          << " s is above the critical time step of central differences for this discretization and material, "
          << critical_step_ << " s (2 / omega_max by Lanczos" << (beta_ > 0 ? ", with stiffness damping" : "")
          << "); expected dt <= " << critical_step_ << " s, or an implicit integrator (or solve.allow_unstable_dt: true to "
          << "run it anyway)";
      throw SharedFailure(why.str());
    }
    fresh_estimate_ = false;
    SolverState& x = working(s);
    x.u = Vector::Zero(layout_->size());
    x.v = Vector::Zero(layout_->size());
    for (const DirichletDof& d : layout_constrained_) x.u[d.dof] = d.value;
    layout_->external_force(0.0, f_ext_);
    layout_->internal_force(x.u, f_int_);
    acceleration(x.v, x.a);
    complete_state(s);
  }

  /// One step of dt, in substeps_ equal substeps when a cut lowered the critical step below dt.
  void advance(SolverState& s, double dt) override {
    const double t0 = s.t, h = dt / substeps_;
    SolverState& x = working(s);
    for (int k = 1; k <= substeps_; ++k) substep(x, h, k == substeps_ ? t0 + dt : t0 + k * h);
    s.t = x.t;
    ++s.step;
    if (!layout_->all_finite(x.u))
      throw Diverged(detail::concat("central-difference step ", s.step, " (t = ", s.t,
                                    " s): the displacement became NaN or infinite: the explicit solution diverged"));
  }

  /// The state's whole vectors from the piece's. Collective.
  void complete_state(SolverState& s) override {
    layout_->to_whole(piece_state_.u, s.u);
    layout_->to_whole(piece_state_.v, s.v);
    layout_->to_whole(piece_state_.a, s.a);
  }
  void complete_displacement_at(SolverState& s, std::span<const Index> dofs) override {
    layout_->to_whole_at(piece_state_.u, dofs, s.u);
  }

  void applied_changed(SolverState& s) override {
    constrained_ = mechanics_.dirichlet(s.t);
    layout_constrained_ = layout_->constrained(constrained_);
    SolverState& x = working(s);
    // Prescribed values move only with a contact sphere, and a body with spheres is laid out whole: `moved`
    // is the same on every rank (a piece layout's force evaluation is collective).
    bool moved = false;  // v and a stay zero at prescribed dofs
    for (const DirichletDof& d : layout_constrained_)
      if (x.u[d.dof] != d.value) x.u[d.dof] = d.value, moved = true;
    // The next step starts from the acceleration of the new loads, and of the new state when a value moved
    // (a force evaluation then; new loads alone keep the step's own f_int).
    if (moved)
      read_forces(x, s.t);
    else
      layout_->external_force(s.t, f_ext_), acceleration(x.v, x.a);
  }

  void discretization_changed(SolverState& s) override {
    // A cut can raise omega_max (steep enriched weights next to its front, a
    // sliver cell of a remesh): the critical step is estimated again (a
    // remeshed body's new stepper has just done so) and a dt above it is taken
    // in equal substeps below it, so a softening cut cannot make the run
    // unstable. Costs a Lanczos run of force evaluations a growth.
    mass_ = layout_->lumped_mass();
    inverse_mass_ = mass_.cwiseInverse();
    whole_mass_ = Vector();  // a piece layout's, of the discretization before the change
    if (!fresh_estimate_) critical_step_ = estimate_critical_step_again();
    fresh_estimate_ = false;
    SolverCounters& solver = report_.solver;
    solver.critical_dt_min_s = std::min(solver.critical_dt_min_s.value_or(critical_step_), critical_step_);
    const double needed = options_.dt / critical_step_;
    // Thousands of substeps a step mean a near-singular discretization, not a stiffer body: stopped, naming where.
    KERF_CHECK_SHARED(options_.allow_unstable_dt || needed <= max_substeps, "central-difference at t = ", s.t,
                      " s: after the cut changed the body its critical time step fell to ", critical_step_, " s; dt = ",
                      options_.dt, " s would take ", needed, " substeps a step, more than the ", max_substeps,
                      " allowed. The fastest vibration is largest at ", mechanics_.describe_dof(fastest_dof()),
                      ": a near-singular shape function within a support of there (a cut through or next to a node?)");
    substeps_ = options_.allow_unstable_dt ? 1 : std::max(1, static_cast<int>(std::ceil(needed)));
    solver.substeps_max = std::max(solver.substeps_max, substeps_);
    // A remeshed body comes with a new stepper, which has read no load yet.
    read_forces(working(s), s.t);
  }

  double kinetic_energy(const SolverState& s) const override {
    return 0.5 * layout_->weighted_square(working(s).v, mass_);
  }
  /// From the whole state (complete_state first).
  Vector reaction(const SolverState& s) override {
    Vector r, f_ext;
    mechanics_.internal_force(s.u, r);
    mechanics_.external_force(s.t, f_ext);
    return r + whole_mass().cwiseProduct(s.a + alpha_ * s.v) - f_ext;
  }
  void applied_load(const SolverState& s, Vector& f) const override { mechanics_.external_force(s.t, f); }
  double time_step() const override { return options_.dt; }
  int step_count() const override {
    return std::max(1, static_cast<int>(std::llround(options_.duration / options_.dt)));
  }
  Vector vibration_mode() const override {
    Vector full = Vector::Zero(mechanics_.dof_count());
    if (mode_.size() > 0) FreeDofs(mechanics_.dof_count(), constrained_).add_to_full(mode_, full);
    return full;
  }

 private:
  /// The stable step with the lumped mass (s): the larger of the element bound
  /// (FEM; safe but often twice too small) and 2 / omega_max by Lanczos on the
  /// stiffness at rest (an upper bound on omega_max), with stiffness damping.
  /// K is never assembled (stiffness_at_rest): on the 207k-dof nodal cube of
  /// the scaling study that took the peak from 1 527 to 292 MB and the set-up
  /// from 7.2 to 2.4 s, at the same step to 1.4e-7 (13 force evaluations).
  double estimate_critical_step() {
    // A partitioned body's bound is over its own cells: the ranks' bounds are combined.
    const RankSum* ranks = mechanics_.rank_sum();
    std::optional<double> element_bound;
    if (const auto* bound = capability<ElementStepBound>(mechanics_.body()))
      element_bound = ranks ? ranks->smallest(bound->critical_time_step()) : bound->critical_time_step();
    report_.add_stage("critical step");
    // Lanczos needs a symmetric K: scene validation refuses VCI with central differences.
    KERF_CHECK(mechanics_.symmetric_tangent(), "internal: central differences with an unsymmetric stiffness");
    const EigenvalueBound omega2 = largest_eigenvalue(stiffness_at_rest(), whole_mass(),
                                                      FreeDofs(mechanics_.dof_count(), constrained_), lanczos_options());
    mode_ = omega2.ritz_vector;
    const double lanczos_step = 2.0 / std::sqrt(omega2.upper_bound);
    const double step = damped_critical_step(std::max(lanczos_step, element_bound.value_or(0.0)), beta_);
    SolverCounters& solver = report_.solver;
    if (solver.critical_dt_s) return step;  // the run's start was reported; later estimates go to critical_dt_min_s
    solver.critical_dt_s = step;
    if (element_bound) solver.critical_dt_element_bound_s = damped_critical_step(*element_bound, beta_);
    return step;
  }

  /// The stable step after the shape functions changed in place: started from
  /// the last estimate's mode and stopped at a 1% residual, which is added:
  /// still an upper bound on omega_max.
  double estimate_critical_step_again() {
    LanczosOptions options = lanczos_options();
    options.tolerance = reestimate_tolerance_;
    options.start = &mode_;
    const EigenvalueBound omega2 =
        largest_eigenvalue(stiffness_at_rest(), whole_mass(), FreeDofs(mechanics_.dof_count(), constrained_), options);
    mode_ = omega2.ritz_vector;
    return damped_critical_step(2.0 / std::sqrt(omega2.upper_bound), beta_);
  }

  /// K x at rest without assembling K, one force evaluation a product: K x is
  /// the derivative of f_int along x at u = 0, so K x = (f_int(e x) - f_int(0)) / e
  /// to first order (exact for a linear material; f_int(0) is zero but where
  /// a sphere presses at rest). Summed over the ranks of a partitioned body.
  StiffnessTimes stiffness_at_rest() {
    mechanics_.internal_force(Vector::Zero(mechanics_.dof_count()), force_at_rest_);
    return [this](const Vector& x, Vector& y) {
      const double e = probe_length_ / std::max(x.lpNorm<Eigen::Infinity>(), 1e-300);
      scaled_ = e * x;
      mechanics_.internal_force(scaled_, y);
      y -= force_at_rest_;
      y /= e;
    };
  }

  /// Lanczos started from a vector fixed by the dofs' positions, not their
  /// numbers: a mesh divided among ranks numbers the nodes otherwise, and
  /// the estimate must not move with it.
  LanczosOptions lanczos_options() const {
    LanczosOptions options;
    options.start_entry = [this](Index dof) {
      const int dim = mechanics_.dofs_per_node();
      const double s = std::sin(mechanics_.dof_position(dof).dot(Vec3(12.9898e3, 78.233e3, 37.719e3)) +
                                1.618 * (dof % dim)) * 43758.5453;
      return 2.0 * (s - std::floor(s)) - 1.0;  // in [-1, 1): as rough as a random vector
    };
    return options;
  }

  /// 1e-7 of the body's bounding-box diagonal (m): the largest displacement a
  /// matrix-free product applies, small enough that f_int stays linear.
  static double probe_length_of(const DiscreteBody& body) {
    Vec3 low = Vec3::Constant(1e300), high = Vec3::Constant(-1e300);
    for (Index I = 0; I < body.node_count(); ++I) {
      low = low.cwiseMin(body.node_position(I));
      high = high.cwiseMax(body.node_position(I));
    }
    return 1e-7 * (high - low).norm();
  }

  /// Where the fastest vibration sits: the free dof where M^-1 K q is largest
  /// for the last estimate's mode q (q may not have converged onto a
  /// near-singular dof yet; its product is dominated by that dof).
  Index fastest_dof() {
    const FreeDofs free(mechanics_.dof_count(), constrained_);
    Vector q = Vector::Zero(mechanics_.dof_count()), force;
    free.add_to_full(mode_, q);
    mechanics_.internal_force(q * (probe_length_ / std::max(q.lpNorm<Eigen::Infinity>(), 1e-300)), force);
    if (free.free_count() == 0) return 0;
    const Vector& mass = whole_mass();
    Index best = free.free_dofs().front();
    for (Index d : free.free_dofs())
      if (std::abs(force[d] / mass[d]) > std::abs(force[best] / mass[best])) best = d;
    return best;
  }

  /// Velocity Verlet over h, ending at time t1: self-starting, so substeps may differ from the steps around them.
  void substep(SolverState& s, double h, double t1) {
    half_velocity_ = s.v + 0.5 * h * s.a;
    zero_constrained(half_velocity_);
    s.u += h * half_velocity_;
    layout_->external_force(t1, f_ext_);
    // f_int(u + beta v) = f_int(u) + beta K v to first order: stiffness damping in one evaluation.
    {
      ScopedTimer timer(report_.phases, Phase::assembly);  // the explicit step's phase studies compare
      if (beta_ != 0.0) {
        damped_u_ = s.u + beta_ * half_velocity_;
        layout_->internal_force(damped_u_, f_int_);
      } else {
        layout_->internal_force(s.u, f_int_);
      }
    }
    acceleration(half_velocity_, s.a);
    s.v = half_velocity_ + 0.5 * h * s.a;
    zero_constrained(s.v);
    s.t = t1;
  }

  /// f_ext(t), f_int at x (with stiffness damping: at u + beta v) and the acceleration they give.
  void read_forces(SolverState& x, double t) {
    layout_->external_force(t, f_ext_);
    if (beta_ != 0.0) {
      damped_u_ = x.u + beta_ * x.v;
      layout_->internal_force(damped_u_, f_int_);
    } else {
      layout_->internal_force(x.u, f_int_);
    }
    acceleration(x.v, x.a);
  }

  /// a = M^-1 (f_ext - f_int - alpha M v), zero at constrained dofs; no allocation once sized.
  void acceleration(const Vector& v, Vector& a) const {
    a = inverse_mass_.cwiseProduct(f_ext_ - f_int_) - alpha_ * v;
    zero_constrained(a);
  }
  void zero_constrained(Vector& x) const {
    for (const DirichletDof& d : layout_constrained_) x[d.dof] = 0.0;
  }

  /// The state the steps advance: the piece's vectors, or the whole state itself.
  SolverState& working(SolverState& s) { return layout_->piece() ? piece_state_ : s; }
  const SolverState& working(const SolverState& s) const { return layout_->piece() ? piece_state_ : s; }
  /// The lumped mass over every dof (the critical step's Lanczos runs on whole vectors).
  const Vector& whole_mass() {
    if (!layout_->piece()) return mass_;
    if (whole_mass_.size() == 0) whole_mass_ = mechanics_.lumped_mass();
    return whole_mass_;
  }

  const MechanicalSystem& mechanics_;
  RunReport& report_;
  SolveOptions options_;
  double alpha_, beta_;
  std::vector<DirichletDof> constrained_;  // over every dof
  std::unique_ptr<ExplicitLayout> layout_;  // where the steps' vectors live: every dof, or this rank's piece
  std::vector<DirichletDof> layout_constrained_;
  SolverState piece_state_;                // u, v, a over the piece's dofs (a piece layout)
  Vector whole_mass_;                      // a piece layout's lumped mass over every dof, when asked
  Vector mass_, inverse_mass_, f_ext_, f_int_, half_velocity_, damped_u_;
  Vector force_at_rest_, scaled_;  // stiffness_at_rest's f_int(0) and e x
  double critical_step_ = 0.0;
  std::string dt_location_;      // where the scene sets solve.dt, for the refusal
  Vector mode_;                  // the last estimate's Ritz vector: the next one starts from it
  double reestimate_tolerance_ = 1e-2;  // Lanczos's stop for estimate_critical_step_again
  double probe_length_ = 0.0;    // m: 1e-7 of the body's diagonal, the matrix-free product's largest displacement
  bool fresh_estimate_ = false;  // critical_step_ is of the discretization as it is now
  int substeps_ = 1;             // per step: ceil(dt / critical_step_) after a growth lowered it
  static constexpr double max_substeps = 1000;
};

}  // namespace

std::unique_ptr<Stepper> make_central_difference_stepper(MechanicalSystem& mechanics, const StepperSettings& settings,
                                                         RunReport& report, const Vector& carried_mode) {
  return std::make_unique<CentralDifferenceStepper>(mechanics, settings, report, carried_mode);
}

}  // namespace kerf
