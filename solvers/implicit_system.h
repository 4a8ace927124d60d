#pragma once
// The matrices of an implicit step over all dofs: K(u) and, when asked, the
// mass M (lumped or consistent, same pattern as K). Forms A = c_M M + c_K K
// on the free dofs and solves with it (a backend that copies the matrix,
// PETSc, reads A's rows straight from K and M instead: kerf then holds no
// A_ff beside its copy), skipping work that cannot have changed: a linear
// body assembles K once (with contact, its elastic part), an unchanged A is
// not factorized again, and with a direct backend a changed A is first
// solved by conjugate gradients preconditioned with the last factorization,
// refactorizing only when those need more than a few iterations (the answer
// is the same to the tolerance). A body whose stiffness is not symmetric
// (nodal integration with VCI) is solved by GMRES preconditioned with the
// backend's factorization of its Galerkin counterpart (test functions equal
// to the trial ones: symmetric, and positive definite when the body is held;
// A's own symmetric part need not be); serial only for now.
#include <memory>

#include "core/check.h"
#include "core/run_report.h"
#include "solvers/linear_solver.h"
#include "solvers/mechanical_system.h"
#include "solvers/solution_history.h"
#include "solvers/sparse_assembly.h"

namespace kerf {

/// A factorization that failed at this state (the matrix singular or
/// indefinite there): a smaller increment may pass, so a stepper may retry.
/// Every rank meets it alike (PETSc's verdict on a shared solve).
class FactorizationFailed : public SharedFailure {
 public:
  using SharedFailure::SharedFailure;
};

class ImplicitSystem {
 public:
  ImplicitSystem(MechanicalSystem& mechanics, const SolveOptions& options, bool needs_mass, RunReport& report);

  const FreeDofs& free() const { return free_; }
  const MechanicalSystem& mechanics() const { return mechanics_; }

  /// f_int(u) into f (all dofs). With `with_tangent`, K(u) is assembled too.
  /// A linear body assembles K once and computes f = K u.
  void internal_force(const Vector& u, Vector& f, bool with_tangent);
  /// M x and K x over all dofs (K: the last assembled).
  Vector mass_times(const Vector& x) const;
  Vector stiffness_times(const Vector& x) const;
  /// A x over all dofs, with A as last formed by update_matrix.
  Vector system_times(const Vector& x) const;

  /// Forms A = c_M M + c_K K on the free dofs; factorizes it unless the last
  /// factorization can precondition it (same coefficients, direct backend).
  void update_matrix(double mass_coefficient, double stiffness_coefficient, const std::string& where);
  /// The body's shape functions changed (a cut grew): K and M are read anew.
  void discretization_changed();
  /// x_f = A_ff^-1 b_f (to solve.linear_tolerance when solved iteratively).
  Vector solve(const Vector& rhs_free, const std::string& where);

 private:
  MechanicalSystem& mechanics_;
  RunReport& report_;
  FreeDofs free_;
  SparseMatrix stiffness_;
  std::vector<double> mass_values_;  // consistent mass in the pattern of K
  std::vector<double> linear_values_;  // a linear body's own stiffness (with contact) in the pattern of K
  Vector lumped_mass_;
  Vector own_lumped_mass_;  // this rank's rows of it (all of it unless the matrix is partial)
  bool has_mass_ = false;
  bool lumped_ = false;
  bool stiffness_assembled_ = false;
  bool stiffness_changed_ = true;
  double last_mass_coefficient_ = -1.0, last_stiffness_coefficient_ = -1.0;
  bool analyzed_ = false;
  bool reuse_factorization_ = false;  // direct backend kerf holds A_ff for: precondition CG with a stale factor
  bool symmetric_ = true;  // false: GMRES on A, the factor of its Galerkin counterpart preconditioning
  SparseMatrix galerkin_;  // the Galerkin tangent, in K's pattern, when K is not symmetric
  bool factor_stale_ = false;         // A changed since the last factorization
  bool factor_failed_ = false;        // the last factorization failed: nothing to precondition with
  double linear_tolerance_;           // relative residual of the preconditioned CG
  Vector previous_solution_;          // warm start of the next GMRES
  // The start of the next preconditioned CG. Eight: on the 6 786-node block
  // (BM_ImplicitEulerStepCorotationalCholmod/2) 4.05 CG iterations a step with
  // the last solution alone, 2.65 with 6, 2.53 with 8, no fewer with 12 or 16.
  SolutionHistory recent_solutions_{8};
  std::unique_ptr<LinearSolver> solver_;
  TangentKind tangent_ = TangentKind::automatic;
  Vector tangent_point_;  // u of the last tangent (solve.tangent: auto), to assemble the definite one there

  /// A x for values of A in K's pattern, whole on every rank (a partial
  /// matrix's products are summed over the ranks).
  Vector times(const double* values, const Vector& x) const;
  /// A = c_M M + c_K K on the free dofs (a partial matrix: this rank's part).
  void combine(double cm, double ck);
  void read_mass();
  void remember_solution(const Vector& x);
  enum class BackendStep { analyze, factorize };
  /// The backend's analysis or factorization of A: A_ff as formed, or, for a
  /// backend that copies the matrix (PETSc), A's rows read from K and M.
  LinearSolverStatus backend_takes(BackendStep step);
  /// Factorizes A; with solve.tangent: auto, a failed factorization of a
  /// nonlinear body's tangent is retried once with the definite tangent.
  void factorize_now(const std::string& where);
  bool falls_back_to_definite() const;
  /// K at the last tangent's u with the definite material tangent, and A from it.
  void assemble_definite_tangent();
  /// Conjugate gradients on A_ff preconditioned by the stale factor; false if
  /// it needs more than the allowed iterations.
  bool preconditioned_cg(const Vector& b, Vector& x, const std::string& where);
  /// GMRES on A_ff (not symmetric) preconditioned by the (maybe stale) factor of its Galerkin counterpart.
  Vector solve_unsymmetric(const Vector& b, const std::string& where);
  /// K assembled: the Galerkin counterpart too when K is not symmetric.
  void stiffness_assembled(const Vector& u);
};

}  // namespace kerf
