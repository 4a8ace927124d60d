// PETSc KSP on a parallel AIJ matrix (solvers/petsc_solver.h): inside the PETSc module.
#include <petscksp.h>

#include <cstdlib>
#include <optional>
#include <vector>

#include "core/check.h"
#include "solvers/petsc_internals.h"

namespace kerf {
namespace {

class PetscSolver final : public LinearSolver {
 public:
  PetscSolver(std::string options, double tolerance) : options_(std::move(options)), tolerance_(tolerance) {
    start_petsc();
  }
  ~PetscSolver() override {
    if (ksp_) KSPDestroy(&ksp_);
    if (matrix_) MatDestroy(&matrix_);
    if (b_) VecDestroy(&b_);
    if (x_) VecDestroy(&x_);
    if (gather_) VecScatterDestroy(&gather_);
    if (all_) VecDestroy(&all_);
  }
  std::string name() const override { return "petsc"; }
  void set_near_null_space(const std::vector<Vector>& modes) override { near_null_space_ = modes; }
  void set_row_share(const RowShare& share) override { share_ = share; }

  bool copies_matrix() const override { return true; }
  LinearSolverStatus analyze(const SparseMatrix& pattern) override { return analyze_rows(StoredRows(pattern)); }
  LinearSolverStatus factorize(const SparseMatrix& A) override { return factorize_rows(StoredRows(A)); }

  LinearSolverStatus analyze_rows(const MatrixRows& pattern) override {
    const PetscInt n = static_cast<PetscInt>(pattern.size());
    PetscInt local = share_ ? share_->owned_end - share_->owned_begin : PETSC_DECIDE, global = n;
    petsc_check(PetscSplitOwnership(PETSC_COMM_WORLD, &local, &global), "PetscSplitOwnership");
    petsc_check(MatCreate(PETSC_COMM_WORLD, &matrix_), "MatCreate");
    petsc_check(MatSetSizes(matrix_, local, local, n, n), "MatSetSizes");
    petsc_check(MatSetType(matrix_, MATAIJ), "MatSetType");
    // Whole nodes: GAMG aggregates nodes (the block size elasticity wants).
    if (share_ && share_->block_size > 1) petsc_check(MatSetBlockSize(matrix_, share_->block_size), "MatSetBlockSize");
    PetscInt first = 0, end = 0;
    petsc_check(MatSetUp(matrix_), "MatSetUp");
    petsc_check(MatGetOwnershipRange(matrix_, &first, &end), "MatGetOwnershipRange");
    // Diagonal-block and off-diagonal-block counts of the rows this rank owns.
    std::vector<PetscInt> d_nnz(end - first, 0), o_nnz(end - first, 0);
    std::vector<Index> columns;
    std::vector<double> values;
    for (PetscInt r = first; r < end; ++r) {
      pattern.row(static_cast<Index>(r), columns, values);
      for (const Index c : columns) (c >= first && c < end ? d_nnz : o_nnz)[r - first]++;
    }
    // Counted in blocks of whole nodes, whose rows share one pattern.
    const PetscInt bs = share_ ? share_->block_size : 1;
    for (PetscInt b = 0; b < (end - first) / bs; ++b) {
      d_nnz[b] = d_nnz[b * bs] / bs;
      o_nnz[b] = o_nnz[b * bs] / bs;
    }
    petsc_check(MatXAIJSetPreallocation(matrix_, bs, d_nnz.data(), o_nnz.data(), nullptr, nullptr),
                "MatXAIJSetPreallocation");
    petsc_check(MatSetOption(matrix_, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
    petsc_check(MatSetOption(matrix_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
    // Partial matrices send the same ghost rows at every assembly: PETSc keeps the communication's pattern.
    if (partial()) petsc_check(MatSetOption(matrix_, MAT_SUBSET_OFF_PROC_ENTRIES, PETSC_TRUE), "MatSetOption");
    first_ = first;
    end_ = end;
    petsc_check(MatCreateVecs(matrix_, &x_, &b_), "MatCreateVecs");
    attach_near_null_space();
    petsc_check(VecScatterCreateToAll(x_, &gather_, &all_), "VecScatterCreateToAll");

    petsc_check(KSPCreate(PETSC_COMM_WORLD, &ksp_), "KSPCreate");
    petsc_check(KSPSetTolerances(ksp_, tolerance_, 1e-50, PETSC_DEFAULT, 10000), "KSPSetTolerances");
    petsc_check(PetscOptionsClear(nullptr), "PetscOptionsClear");
    PetscErrorCode code = PetscOptionsInsertString(nullptr, options_.c_str());
    if (code) return LinearSolverStatus::failure("petsc: cannot parse the options '" + options_ + "'");
    petsc_check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
    return LinearSolverStatus::success();
  }

  LinearSolverStatus factorize_rows(const MatrixRows& A) override {
    std::vector<Index> columns;
    std::vector<double> values;
    std::vector<PetscInt> cols;  // PetscInt may be wider than kerf's Index
    auto set_row = [&](PetscInt r, InsertMode mode) {
      A.row(static_cast<Index>(r), columns, values);
      cols.assign(columns.begin(), columns.end());
      petsc_check(MatSetValues(matrix_, 1, &r, static_cast<PetscInt>(cols.size()), cols.data(), values.data(), mode),
                  "MatSetValues");
    };
    if (partial()) {
      // This rank's part of every row its cells touch; PETSc adds the ranks' parts.
      petsc_check(MatZeroEntries(matrix_), "MatZeroEntries");
      for (Index r : share_->touched) set_row(r, ADD_VALUES);
    } else {
      for (PetscInt r = first_; r < end_; ++r) set_row(r, INSERT_VALUES);
    }
    petsc_check(MatAssemblyBegin(matrix_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    petsc_check(MatAssemblyEnd(matrix_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    petsc_check(KSPSetOperators(ksp_, matrix_, matrix_), "KSPSetOperators");
    PetscErrorCode code = KSPSetUp(ksp_);
    if (code) {
      const char* text = nullptr;
      PetscErrorMessage(code, &text, nullptr);
      return LinearSolverStatus::failure(std::string("petsc: KSPSetUp failed (") + (text ? text : "") +
                                         "): the matrix may be singular or the options unsuitable");
    }
    if (!checked_options_) {
      checked_options_ = true;
      PetscInt count = 0;
      char** names = nullptr;
      char** values = nullptr;
      petsc_check(PetscOptionsLeftGet(nullptr, &count, &names, &values), "PetscOptionsLeftGet");
      std::string unused;
      for (PetscInt i = 0; i < count; ++i)
        if (std::string(names[i]) != "no_signal_handler") unused += " -" + std::string(names[i]);
      petsc_check(PetscOptionsLeftRestore(nullptr, &count, &names, &values), "PetscOptionsLeftRestore");
      if (!unused.empty())
        return LinearSolverStatus::failure("petsc: option(s)" + unused + " in '" + options_ +
                                           "' were never used: misspelled, or not for this KSP/PC");
    }
    return LinearSolverStatus::success();
  }

  LinearSolverStatus solve(const Vector& b, Vector& x) override {
    PetscScalar* bb = nullptr;
    petsc_check(VecGetArray(b_, &bb), "VecGetArray");
    for (PetscInt r = first_; r < end_; ++r) bb[r - first_] = b[r];
    petsc_check(VecRestoreArray(b_, &bb), "VecRestoreArray");
    petsc_check(KSPSolve(ksp_, b_, x_), "KSPSolve");
    KSPConvergedReason reason;
    petsc_check(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason");
    PetscInt iterations = 0;
    petsc_check(KSPGetIterationNumber(ksp_, &iterations), "KSPGetIterationNumber");
    iterations_ = static_cast<int>(iterations);
    if (reason < 0)
      return LinearSolverStatus::failure(std::string("petsc: KSP diverged (") + KSPConvergedReasons[reason] +
                                         ") after " + std::to_string(iterations) + " iterations");
    petsc_scatter_into(gather_, x_, all_, b.size(), x);
    return LinearSolverStatus::success();
  }
  int last_iterations() const override { return iterations_; }

 private:
  /// Rigid-body modes as PETSc's near-null space: GAMG builds its coarse
  /// spaces from them (elasticity converges poorly without).
  void attach_near_null_space() {
    if (near_null_space_.empty()) return;
    std::vector<Vec> vectors(near_null_space_.size());
    for (std::size_t k = 0; k < vectors.size(); ++k) {
      petsc_check(VecDuplicate(x_, &vectors[k]), "VecDuplicate");
      PetscScalar* v = nullptr;
      petsc_check(VecGetArray(vectors[k], &v), "VecGetArray");
      for (PetscInt r = first_; r < end_; ++r) v[r - first_] = near_null_space_[k][r];
      petsc_check(VecRestoreArray(vectors[k], &v), "VecRestoreArray");
    }
    MatNullSpace space = nullptr;
    petsc_check(MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_FALSE, static_cast<PetscInt>(vectors.size()), vectors.data(),
                             &space),
          "MatNullSpaceCreate");
    petsc_check(MatSetNearNullSpace(matrix_, space), "MatSetNearNullSpace");
    petsc_check(MatNullSpaceDestroy(&space), "MatNullSpaceDestroy");
    for (Vec& v : vectors) petsc_check(VecDestroy(&v), "VecDestroy");
  }

  bool partial() const { return share_ && share_->partial; }

  std::vector<Vector> near_null_space_;
  std::optional<RowShare> share_;
  std::string options_;
  double tolerance_;
  Mat matrix_ = nullptr;
  Vec b_ = nullptr, x_ = nullptr, all_ = nullptr;
  VecScatter gather_ = nullptr;
  KSP ksp_ = nullptr;
  PetscInt first_ = 0, end_ = 0;
  bool checked_options_ = false;
  int iterations_ = 0;
};

}  // namespace

std::unique_ptr<LinearSolver> petsc_ksp_solver(const std::string& options, double relative_tolerance) {
  return std::make_unique<PetscSolver>(options, relative_tolerance);
}

}  // namespace kerf
