#include "solvers/implicit_system.h"

#include <algorithm>

#include "core/check.h"
#include "core/gmres.h"
#include "solvers/free_system_rows.h"
#include "solvers/linear_prolongation.h"

namespace kerf {

// A solve's verdict (PETSc's reason, a norm of the replicated solution) is
// the same on every MPI rank: those checks are KERF_CHECK_SHARED.
namespace {

/// Translations and infinitesimal rotations on the free dofs, orthonormalised.
std::vector<Vector> rigid_body_modes(const MechanicalSystem& mechanics, const FreeDofs& free) {
  const int dim = mechanics.dofs_per_node();
  std::vector<Vector> modes;
  auto add = [&](auto&& mode_at) {
    Vector v(free.free_count());
    for (Index i = 0; i < free.free_count(); ++i) {
      Index dof = free.free_dofs()[i];
      v[i] = mode_at(mechanics.dof_position(dof))[dof % dim];
    }
    for (const Vector& m : modes) v -= m.dot(v) * m;  // Gram-Schmidt
    if (v.norm() > 1e-12 * std::sqrt(static_cast<double>(v.size()))) modes.push_back(v.normalized());
  };
  for (int axis = 0; axis < dim; ++axis) add([&](const Vec3&) { return Vec3(Vec3::Unit(axis)); });
  for (int axis = dim == 3 ? 0 : 2; axis < 3; ++axis)
    add([&](const Vec3& x) { return Vec3(Vec3::Unit(axis).cross(x)); });
  return modes;
}

/// The linear functions of the body's quadratic cells on the free dofs (p-multigrid's coarse space).
SparseMatrix coarse_space(const MechanicalSystem& mechanics, const FreeDofs& free) {
  const MeshedBody* meshed = capability<MeshedBody>(mechanics.body());
  KERF_CHECK(meshed && meshed->mesh().order == 2 && mechanics.dof_count() == mechanics.body().dof_count(),
             "solve.linear_solver: p_multigrid needs a finite-element body of quadratic cells (tet10 or tri6) "
             "whose nodes carry every dof");
  const Mesh& mesh = meshed->mesh();
  std::vector<Index> split_nodes;  // the coarse level solves them exactly (linear_prolongation.h)
  for (Index c = 0; c < mesh.cell_count(); ++c)
    if (meshed->fragment_cell(c)) split_nodes.insert(split_nodes.end(), mesh.cell(c).begin(), mesh.cell(c).end());
  return corner_prolongation(mesh, free, mechanics.dofs_per_node(), split_nodes);
}

/// Whether every node (and every term's block) has all its dofs free or none.
bool free_in_whole_nodes(const FreeDofs& free, Index dof_count, int dim) {
  if (dof_count % dim != 0) return false;
  for (Index first = 0; first < dof_count; first += dim)
    for (int i = 1; i < dim; ++i)
      if ((free.free_index(first + i) >= 0) != (free.free_index(first) >= 0)) return false;
  return true;
}

/// The dofs' share in the numbering of the free dofs (ascending with the dofs).
RowShare free_rows(const RowShare& dofs, const FreeDofs& free, Index dof_count, int dim) {
  RowShare rows;
  rows.partial = dofs.partial;
  rows.block_size = free_in_whole_nodes(free, dof_count, dim) ? dim : 1;
  const std::vector<Index>& all = free.free_dofs();
  rows.owned_begin = static_cast<Index>(std::lower_bound(all.begin(), all.end(), dofs.owned_begin) - all.begin());
  rows.owned_end = static_cast<Index>(std::lower_bound(all.begin(), all.end(), dofs.owned_end) - all.begin());
  for (Index d : dofs.touched)
    if (free.free_index(d) >= 0) rows.touched.push_back(free.free_index(d));
  return rows;
}

}  // namespace

ImplicitSystem::ImplicitSystem(MechanicalSystem& mechanics, const SolveOptions& options, bool needs_mass,
                               RunReport& report)
    : mechanics_(mechanics), report_(report), free_(mechanics.dof_count(), mechanics.dirichlet(0.0)) {
  ScopedTimer timer(report_.phases, Phase::setup);
  KERF_CHECK(free_.free_count() > 0, "every degree of freedom is prescribed: nothing to solve");
  SparseMatrix pattern = build_pattern(mechanics_);
  stiffness_.swap(pattern);  // Eigen's SparseMatrix has no move assignment: `=` would copy it
  LinearSolverOptions linear;
  linear.kind = options.linear_solver;
  linear.petsc_options = options.petsc;
  if (!options.petsc_written && mechanics_.ranks().distributed()) {
    linear.petsc_options += petsc_rank_options;
    report_.notes.push_back("solve.petsc: not written, so on " + std::to_string(mechanics_.ranks().count) +
                            " MPI ranks '" + linear.petsc_options + "' (GAMG's memory divided among the ranks; "
                            "docs/parallel.md)");
  }
  linear.relative_tolerance = options.linear_tolerance;
  linear_tolerance_ = options.linear_tolerance;
  solver_ = make_linear_solver(linear, report_);
  if (!solver_->copies_matrix()) free_.prepare_matrix(stiffness_);  // A_ff formed by kerf (else backend_takes)
  solver_->set_near_null_space(rigid_body_modes(mechanics_, free_));
  if (solver_->needs_prolongation()) solver_->set_prolongation(coarse_space(mechanics_, free_));
  solver_->set_row_share(free_rows(mechanics_.dof_share(), free_, mechanics_.dof_count(), mechanics_.dofs_per_node()));
  symmetric_ = mechanics_.symmetric_tangent();
  KERF_CHECK(symmetric_ || !mechanics_.dof_share().partial,
             "discretization.meshless.vci: linear makes nodal integration's stiffness unsymmetric, which the implicit "
             "solve across MPI ranks does not take yet; expected discretization.meshless.vci: none for an implicit or "
             "static run under mpirun (explicit runs take VCI on any number of ranks)");
  reuse_factorization_ = symmetric_ && !mechanics_.is_linear() && solver_->exact_factor() && !solver_->copies_matrix();
  // The stale factor only preconditions: its single-precision copy streams half
  // the bytes, on two threads. 6 786-node block: the solve phase 22.4 -> 16.6 ms
  // a step (one thread), 10.6-11.1 (two), CG iterations unchanged; nearly
  // incompressible (nu = 0.499) corotational tet10 cantilever, 73 Newton
  // iterations: 1 338 -> 1 302 CG iterations, 46 -> 49 factorizations.
  if (reuse_factorization_) solver_->keep_single_precision_copy();
  tangent_ = options.tangent;
  mechanics_.use_definite_tangent(tangent_ == TangentKind::definite);
  if (needs_mass) {
    has_mass_ = true;
    lumped_ = options.mass == MassKind::lumped;
    read_mass();
  }
}

void ImplicitSystem::read_mass() {
  report_.add_stage("mass");
  if (lumped_) {
    lumped_mass_ = mechanics_.lumped_mass();
    // Whole on every rank: a partial matrix takes it on its own rows only.
    const RowShare& share = mechanics_.dof_share();
    own_lumped_mass_ = lumped_mass_;
    if (share.partial) {
      own_lumped_mass_.head(share.owned_begin).setZero();
      own_lumped_mass_.tail(own_lumped_mass_.size() - share.owned_end).setZero();
    }
    return;
  }
  SparseMatrix mass = stiffness_;
  std::fill(mass.valuePtr(), mass.valuePtr() + mass.nonZeros(), 0.0);
  mechanics_.consistent_mass(add_into(mass, 1.0, mechanics_.dofs_per_node()));
  mass_values_.assign(mass.valuePtr(), mass.valuePtr() + mass.nonZeros());
}

void ImplicitSystem::discretization_changed() {
  // Same dofs and pattern: K is assembled again (a linear body's too) and A re-formed and refactorized.
  std::fill(stiffness_.valuePtr(), stiffness_.valuePtr() + stiffness_.nonZeros(), 0.0);
  stiffness_assembled_ = false;
  stiffness_changed_ = true;
  linear_values_.clear();
  last_mass_coefficient_ = last_stiffness_coefficient_ = -1.0;
  if (has_mass_) read_mass();
}

void ImplicitSystem::internal_force(const Vector& u, Vector& f, bool with_tangent) {
  ScopedTimer timer(report_.phases, Phase::assembly);
  if (mechanics_.linear_body_with_terms()) {
    // A linear body with contact: the body's stiffness once, the rest at every call.
    if (linear_values_.empty()) {
      report_.add_stage("stiffness");
      SparseMatrix K = stiffness_;
      std::fill(K.valuePtr(), K.valuePtr() + K.nonZeros(), 0.0);
      const DiscreteBody& body = mechanics_.body();
      const Vector rest = Vector::Zero(body.dof_count());
      if (const MatrixAssembly* direct = capability<MatrixAssembly>(body))  // K is zero: symmetric, as it asks
        direct->add_tangent_into(rest, csr_view(K), nullptr);
      else
        body.tangent(rest, add_into(K, 1.0, body.dofs_per_node()), nullptr);
      linear_values_.assign(K.valuePtr(), K.valuePtr() + K.nonZeros());
    }
    Eigen::Map<const SparseMatrix> K(stiffness_.rows(), stiffness_.cols(), stiffness_.nonZeros(),
                                     stiffness_.outerIndexPtr(), stiffness_.innerIndexPtr(), linear_values_.data());
    f = K * u;
    const RankSum* parts = mechanics_.rank_sum();  // a partitioned rank's K u and terms are its part
    if (!with_tangent) {
      mechanics_.add_terms(u, f, nullptr);
      if (parts) parts->sum(f);
      return;
    }
    std::copy(linear_values_.begin(), linear_values_.end(), stiffness_.valuePtr());
    const BlockSink sink = add_into(stiffness_, 1.0, mechanics_.dofs_per_node());
    mechanics_.add_terms(u, f, &sink);
    if (parts) parts->sum(f);
    stiffness_assembled(u);
    return;
  }
  if (mechanics_.is_linear()) {
    if (!stiffness_assembled_) {
      report_.add_stage("stiffness");
      mechanics_.tangent_into(u, stiffness_, nullptr);
      stiffness_assembled(u);
    }
    f = times(stiffness_.valuePtr(), u);
    return;
  }
  if (!with_tangent) {
    mechanics_.internal_force(u, f);
    return;
  }
  report_.add_stage("stiffness");
  std::fill(stiffness_.valuePtr(), stiffness_.valuePtr() + stiffness_.nonZeros(), 0.0);
  mechanics_.tangent_into(u, stiffness_, &f);
  stiffness_assembled(u);
  if (tangent_ == TangentKind::automatic) tangent_point_ = u;
}

bool ImplicitSystem::falls_back_to_definite() const {
  return tangent_ == TangentKind::automatic && !mechanics_.body().is_linear() &&
         tangent_point_.size() == mechanics_.dof_count();
}

void ImplicitSystem::assemble_definite_tangent() {
  ScopedTimer timer(report_.phases, Phase::assembly);
  std::fill(stiffness_.valuePtr(), stiffness_.valuePtr() + stiffness_.nonZeros(), 0.0);
  mechanics_.use_definite_tangent(true);
  mechanics_.tangent_into(tangent_point_, stiffness_, nullptr);
  stiffness_assembled(tangent_point_);
  mechanics_.use_definite_tangent(false);  // the next iteration tries the exact tangent again
  combine(last_mass_coefficient_, last_stiffness_coefficient_);
  stiffness_changed_ = false;
  report_.solver.definite_tangent_fallbacks += 1;
}

Vector ImplicitSystem::mass_times(const Vector& x) const {
  KERF_DCHECK(has_mass_);
  if (lumped_) return lumped_mass_.cwiseProduct(x);
  return times(mass_values_.data(), x);
}

Vector ImplicitSystem::stiffness_times(const Vector& x) const { return times(stiffness_.valuePtr(), x); }

Vector ImplicitSystem::system_times(const Vector& x) const {
  const double cm = last_mass_coefficient_, ck = last_stiffness_coefficient_;
  KERF_CHECK(ck >= 0.0, "internal: A x before A was formed");
  Vector y = ck * stiffness_times(x);
  if (has_mass_ && cm != 0.0) y += cm * mass_times(x);
  return y;
}

Vector ImplicitSystem::times(const double* values, const Vector& x) const {
  // A partial matrix's pattern holds its touched rows alone (the others a zero diagonal).
  Eigen::Map<const SparseMatrix> A(stiffness_.rows(), stiffness_.cols(), stiffness_.nonZeros(),
                                   stiffness_.outerIndexPtr(), stiffness_.innerIndexPtr(), values);
  Vector y = A * x;
  if (const RankSum* sum = mechanics_.rank_sum()) sum->sum(y);
  return y;
}

void ImplicitSystem::update_matrix(double cm, double ck, const std::string& where) {
  if (!stiffness_changed_ && cm == last_mass_coefficient_ && ck == last_stiffness_coefficient_) return;
  KERF_CHECK(stiffness_assembled_ || ck == 0.0, "internal: matrix update before the stiffness was assembled");
  {
    ScopedTimer timer(report_.phases, Phase::assembly);
    combine(cm, ck);
  }
  const bool same_coefficients = cm == last_mass_coefficient_ && ck == last_stiffness_coefficient_;
  stiffness_changed_ = false;
  last_mass_coefficient_ = cm;
  last_stiffness_coefficient_ = ck;
  if (reuse_factorization_ && analyzed_ && same_coefficients && !factor_failed_) {
    factor_stale_ = true;
    return;
  }
  factorize_now(where);
}

void ImplicitSystem::combine(double cm, double ck) {
  if (solver_->copies_matrix()) return;  // the backend reads A's rows from K and M (backend_takes)
  // Straight into A_ff (no whole-dof copy of A: the largest array a run holds).
  // An unsymmetric A is applied through system_times: A_ff holds what is factorized.
  const double* k = symmetric_ ? stiffness_.valuePtr() : galerkin_.valuePtr();
  const double* m = mass_values_.data();
  if (cm != 0.0 && !lumped_)
    free_.restrict_values_with([=](Index p) { return ck * k[p] + cm * m[p]; });
  else
    free_.restrict_values_with([=](Index p) { return ck * k[p]; });
  if (cm != 0.0 && lumped_) free_.add_to_diagonal(cm, own_lumped_mass_);
}

void ImplicitSystem::factorize_now(const std::string& where) {
  ScopedTimer timer(report_.phases, Phase::factorize);
  if (!analyzed_) {
    LinearSolverStatus status = backend_takes(BackendStep::analyze);
    KERF_CHECK_SHARED(status.ok, where, ": ", status.message);
    analyzed_ = true;
  }
  report_.add_stage("factorization");
  report_.solver.factorizations += 1;
  LinearSolverStatus status = backend_takes(BackendStep::factorize);
  const bool fell_back = !status.ok && falls_back_to_definite();
  if (fell_back) {
    // An exact hyperelastic tangent under compression is indefinite: this
    // iteration takes the definite one (same residual, slower convergence).
    assemble_definite_tangent();
    report_.solver.factorizations += 1;
    status = backend_takes(BackendStep::factorize);
  }
  factor_failed_ = !status.ok;
  if (!status.ok && status.failed_row && *status.failed_row < free_.free_count()) {
    const Index dof = free_.free_dofs()[*status.failed_row];
    const std::string indefinite =
        fell_back ? "its definite tangent failed too, so the body is not held there"
        : tangent_ == TangentKind::exact
            ? "or its stiffness is indefinite there (a nonlinear material under compression: solve.tangent: auto or "
              "definite makes it positive semidefinite)"
            : "";
    throw FactorizationFailed(where + ": " + status.message + "; " + mechanics_.describe_dof(dof) +
                              ". The body is singular there (too few conditions to hold it still)" +
                              (indefinite.empty() ? "" : ", " + indefinite));
  }
  KERF_CHECK_SHARED(status.ok, where, ": ", status.message);  // not the matrix's fault (a backend's set-up)
  factor_stale_ = false;
}

LinearSolverStatus ImplicitSystem::backend_takes(BackendStep step) {
  const bool analyze = step == BackendStep::analyze;
  if (!solver_->copies_matrix())
    return analyze ? solver_->analyze(free_.restricted()) : solver_->factorize(free_.restricted());
  // As combine() forms A_ff, read row by row from K (or its Galerkin counterpart) and M.
  const double cm = last_mass_coefficient_, ck = last_stiffness_coefficient_;
  const FreeSystemRows rows(stiffness_, free_, ck, symmetric_ ? stiffness_.valuePtr() : galerkin_.valuePtr(), cm,
                            cm != 0.0 && !lumped_ ? mass_values_.data() : nullptr,
                            cm != 0.0 && lumped_ ? &own_lumped_mass_ : nullptr);
  return analyze ? solver_->analyze_rows(rows) : solver_->factorize_rows(rows);
}

bool ImplicitSystem::preconditioned_cg(const Vector& b, Vector& x, const std::string& where) {
  constexpr int max_iterations = 20;
  const double tolerance = linear_tolerance_;
  const SparseMatrix& A = free_.restricted();
  const double b_norm = b.norm();
  if (b_norm == 0.0) {
    x = Vector::Zero(b.size());
    return true;
  }
  Vector r, z, p, Ap;
  // Successive steps solve similar systems: start from the best combination
  // of the last solutions in the A-norm (never worse than zero).
  recent_solutions_.start(A, b, x, r);
  auto precondition = [&](const Vector& in, Vector& out) {
    LinearSolverStatus status = solver_->precondition(in, out);
    KERF_CHECK_SHARED(status.ok, where, ": ", status.message);
  };
  precondition(r, z);
  p = z;
  double rz = r.dot(z);
  for (int k = 1; k <= max_iterations; ++k) {
    Ap.noalias() = A * p;
    double pAp = p.dot(Ap);
    if (!(pAp > 0.0)) return false;  // the stale factor no longer fits: refactorize
    double alpha = rz / pAp;
    x += alpha * p;
    r -= alpha * Ap;
    report_.solver.pcg_iterations += 1;
    if (r.norm() <= tolerance * b_norm) return true;
    precondition(r, z);
    double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return false;
}

void ImplicitSystem::stiffness_assembled(const Vector& u) {
  stiffness_assembled_ = true;
  stiffness_changed_ = true;
  if (symmetric_) return;
  if (galerkin_.nonZeros() == 0) galerkin_ = stiffness_;
  std::fill(galerkin_.valuePtr(), galerkin_.valuePtr() + galerkin_.nonZeros(), 0.0);
  mechanics_.galerkin_tangent_into(u, galerkin_);
}

Vector ImplicitSystem::solve_unsymmetric(const Vector& b, const std::string& where) {
  // A_ff x through the whole system (constrained dofs held at zero).
  Vector full = Vector::Zero(mechanics_.dof_count());
  const LinearOperator A = [&](const Vector& x, Vector& y) {
    full.setZero();
    free_.add_to_full(x, full);
    y = free_.restrict_vector(system_times(full));
  };
  const LinearOperator precondition = [&](const Vector& r, Vector& z) {
    LinearSolverStatus status = solver_->solve(r, z);
    KERF_CHECK_SHARED(status.ok, where, ": ", status.message);
  };
  constexpr int restart = 30, max_iterations = 90;
  Vector x = previous_solution_.size() == b.size() ? previous_solution_ : Vector::Zero(b.size());
  GmresResult result;
  {
    ScopedTimer timer(report_.phases, Phase::solve);
    result = gmres(A, precondition, b, x, linear_tolerance_, restart, max_iterations);
  }
  report_.solver.linear_iterations += result.iterations;
  if (!result.converged && factor_stale_) {
    factorize_now(where);
    ScopedTimer timer(report_.phases, Phase::solve);
    result = gmres(A, precondition, b, x, linear_tolerance_, restart, max_iterations);
    report_.solver.linear_iterations += result.iterations;
  }
  KERF_CHECK_SHARED(result.converged && x.allFinite(), where, ": GMRES on the unsymmetric stiffness (VCI) did not converge in ",
                    result.iterations, " iterations (relative residual ", result.relative_residual, ", tolerance ",
                    linear_tolerance_, "): its Galerkin counterpart, the preconditioner, no longer fits it; expected "
                    "discretization.meshless.vci: none or a better-conditioned node set");
  remember_solution(x);
  return x;
}

void ImplicitSystem::remember_solution(const Vector& x) {
  previous_solution_ = x;
  if (reuse_factorization_) recent_solutions_.remember(x);  // only the stale-factor CG starts from them
}

Vector ImplicitSystem::solve(const Vector& rhs_free, const std::string& where) {
  if (!symmetric_) return solve_unsymmetric(rhs_free, where);
  Vector x;
  if (factor_stale_) {
    bool converged;
    {
      ScopedTimer timer(report_.phases, Phase::solve);
      converged = preconditioned_cg(rhs_free, x, where) && x.allFinite();
    }
    if (converged) {
      remember_solution(x);
      return x;
    }
    factorize_now(where);  // timed as "factorize"
  }
  ScopedTimer timer(report_.phases, Phase::solve);
  LinearSolverStatus status = solver_->solve(rhs_free, x);
  KERF_CHECK_SHARED(status.ok, where, ": ", status.message);
  report_.solver.linear_iterations += solver_->last_iterations();
  KERF_CHECK_SHARED(x.allFinite(), where, ": the linear solve returned NaN or infinity (singular matrix?)");
  remember_solution(x);
  return x;
}

}  // namespace kerf
