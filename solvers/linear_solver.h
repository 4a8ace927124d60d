#pragma once
// Sparse symmetric positive-definite solves behind one interface. The matrix is
// row-major CSR with full symmetric storage; its pattern is fixed after analyze().
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/run_report.h"
#include "problem/scene.h"
#include "solvers/row_share.h"
#include "solvers/sparse_assembly.h"

namespace kerf {

struct LinearSolverStatus {
  bool ok = true;
  std::string message;
  std::optional<Index> failed_row;  // a direct solver's failed pivot, in the matrix's numbering
  static LinearSolverStatus success() { return {}; }
  static LinearSolverStatus failure(std::string why) { return {false, std::move(why), std::nullopt}; }
};

/// A matrix handed over one row at a time, for a backend that copies it into
/// its own storage (PETSc): kerf need not form it whole in the backend's numbering.
class MatrixRows {
 public:
  virtual ~MatrixRows() = default;
  /// Rows (the matrix is square).
  virtual Index size() const = 0;
  /// Row r's columns (ascending) and values, replacing what `columns` and `values` held.
  virtual void row(Index r, std::vector<Index>& columns, std::vector<double>& values) const = 0;
};

/// A stored CSR matrix's rows.
class StoredRows final : public MatrixRows {
 public:
  explicit StoredRows(const SparseMatrix& matrix) : matrix_(matrix) {}
  Index size() const override { return static_cast<Index>(matrix_.rows()); }
  void row(Index r, std::vector<Index>& columns, std::vector<double>& values) const override {
    const Index begin = matrix_.outerIndexPtr()[r], end = matrix_.outerIndexPtr()[r + 1];
    columns.assign(matrix_.innerIndexPtr() + begin, matrix_.innerIndexPtr() + end);
    values.assign(matrix_.valuePtr() + begin, matrix_.valuePtr() + end);
  }

 private:
  const SparseMatrix& matrix_;
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  virtual std::string name() const = 0;
  /// Symbolic work on the pattern (ordering, preallocation).
  virtual LinearSolverStatus analyze(const SparseMatrix& pattern) = 0;
  /// Numeric factorization (or preconditioner set-up) of A, same pattern as
  /// analyzed. A stays as it is until the next factorize(): an iterative
  /// backend may keep a reference to it instead of a copy (p_multigrid).
  virtual LinearSolverStatus factorize(const SparseMatrix& A) = 0;
  /// x = A^-1 b for the last factorized A.
  virtual LinearSolverStatus solve(const Vector& b, Vector& x) = 0;
  /// An approximate x = A^-1 b, to precondition with: the single-precision copy
  /// of the factor where the backend keeps one (keep_single_precision_copy), else solve().
  virtual LinearSolverStatus precondition(const Vector& b, Vector& x) { return solve(b, x); }
  /// Keep a single-precision copy of each factor from now on, for precondition() (backends that can).
  virtual void keep_single_precision_copy() {}
  /// Iterations of the last solve (0 for direct solvers).
  virtual int last_iterations() const { return 0; }
  /// Values a direct solver's factor holds (0 when none): each solve streams them twice.
  virtual std::size_t factor_entries() const { return 0; }
  /// Whether solve() applies an exact factorization of the last factorized
  /// matrix, which may then precondition conjugate gradients on a later matrix
  /// of the same pattern instead of factorizing it (direct solvers).
  virtual bool exact_factor() const { return false; }
  /// Vectors the operator nearly annihilates (rigid-body modes), for solvers
  /// that build coarse spaces from them (algebraic multigrid); before analyze().
  virtual void set_near_null_space(const std::vector<Vector>& modes) {}
  /// Whether the backend needs a coarse space (set_prolongation) before analyze(): p-multigrid.
  virtual bool needs_prolongation() const { return false; }
  /// P (free dofs x coarse dofs): the coarse space of a multigrid backend.
  virtual void set_prolongation(const SparseMatrix& P) {}
  /// How the MPI ranks share the rows (before analyze()): solvers that run on
  /// one rank ignore it (the command line refuses them under several).
  virtual void set_row_share(const RowShare& share) {}
  /// Whether the backend copies the matrix into its own storage (PETSc). It
  /// then takes it row by row (analyze_rows, factorize_rows), so that kerf
  /// does not hold a copy of A beside the backend's.
  virtual bool copies_matrix() const { return false; }
  virtual LinearSolverStatus analyze_rows(const MatrixRows& pattern) { return takes_no_rows(); }
  virtual LinearSolverStatus factorize_rows(const MatrixRows& A) { return takes_no_rows(); }

 private:
  LinearSolverStatus takes_no_rows() const {
    return LinearSolverStatus::failure("internal: the " + name() + " backend takes a stored matrix, not rows");
  }
};

/// What a run on several MPI ranks adds to solve.petsc when the scene leaves
/// it out: GAMG's prolongator unsmoothed and its coarse operators built all
/// at once, so that its set-up's memory divides among the ranks (on the
/// 513k-dof tet10 block the largest rank's peak is 0.53, 0.40, 0.33 of one
/// rank's at 2, 3, 4 ranks, against 0.99, 0.70, 0.55 with PETSc's defaults;
/// CG takes about 4 times the iterations). allatonce exists on several ranks alone.
inline constexpr const char* petsc_rank_options = " -pc_gamg_agg_nsmooths 0 -matptap_via allatonce";

struct LinearSolverOptions {
  LinearSolverKind kind = LinearSolverKind::cholmod;
  std::string petsc_options;       // PETSc options database string
  double relative_tolerance = 1e-10;  // iterative solvers (PETSc's own -ksp_rtol wins)
};

/// The one place that knows which backends exist. Records the stages it starts
/// (petsc) in `report`.
std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverOptions& options, RunReport& report);

}  // namespace kerf
