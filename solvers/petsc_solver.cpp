#include "solvers/petsc_solver.h"

#include <petscksp.h>

#include <cstdlib>
#include <vector>

#include "core/check.h"
#include "solvers/petsc_session.h"

namespace kerf {
namespace {

void check(PetscErrorCode code, const char* call) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw Error(std::string("petsc: ") + call + " failed: " + (text ? text : "unknown error") +
              " (code " + std::to_string(code) + ")");
}

class PetscSolver final : public LinearSolver {
 public:
  PetscSolver(std::string options, double tolerance) : options_(std::move(options)), tolerance_(tolerance) {
    ensure_petsc_initialized();
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

  LinearSolverStatus analyze(const SparseMatrix& pattern) override {
    const PetscInt n = static_cast<PetscInt>(pattern.rows());
    PetscInt local = PETSC_DECIDE, global = n;
    check(PetscSplitOwnership(PETSC_COMM_WORLD, &local, &global), "PetscSplitOwnership");
    check(MatCreate(PETSC_COMM_WORLD, &matrix_), "MatCreate");
    check(MatSetSizes(matrix_, local, local, n, n), "MatSetSizes");
    check(MatSetType(matrix_, MATAIJ), "MatSetType");
    PetscInt first = 0, end = 0;
    check(MatSetUp(matrix_), "MatSetUp");
    check(MatGetOwnershipRange(matrix_, &first, &end), "MatGetOwnershipRange");
    // Diagonal-block and off-diagonal-block counts of the rows this rank owns.
    std::vector<PetscInt> d_nnz(end - first, 0), o_nnz(end - first, 0);
    for (PetscInt r = first; r < end; ++r)
      for (Index p = pattern.outerIndexPtr()[r]; p < pattern.outerIndexPtr()[r + 1]; ++p) {
        PetscInt c = pattern.innerIndexPtr()[p];
        (c >= first && c < end ? d_nnz : o_nnz)[r - first]++;
      }
    check(MatXAIJSetPreallocation(matrix_, 1, d_nnz.data(), o_nnz.data(), nullptr, nullptr),
          "MatXAIJSetPreallocation");
    check(MatSetOption(matrix_, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
    check(MatSetOption(matrix_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
    first_ = first;
    end_ = end;
    check(MatCreateVecs(matrix_, &x_, &b_), "MatCreateVecs");
    attach_near_null_space();
    check(VecScatterCreateToAll(x_, &gather_, &all_), "VecScatterCreateToAll");

    check(KSPCreate(PETSC_COMM_WORLD, &ksp_), "KSPCreate");
    check(KSPSetTolerances(ksp_, tolerance_, 1e-50, PETSC_DEFAULT, 10000), "KSPSetTolerances");
    check(PetscOptionsClear(nullptr), "PetscOptionsClear");
    PetscErrorCode code = PetscOptionsInsertString(nullptr, options_.c_str());
    if (code) return LinearSolverStatus::failure("petsc: cannot parse the options '" + options_ + "'");
    check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
    return LinearSolverStatus::success();
  }

  LinearSolverStatus factorize(const SparseMatrix& A) override {
    std::vector<PetscInt> cols;  // PetscInt may be wider than kerf's Index
    for (PetscInt r = first_; r < end_; ++r) {
      Index begin = A.outerIndexPtr()[r], count = A.outerIndexPtr()[r + 1] - begin;
      cols.assign(A.innerIndexPtr() + begin, A.innerIndexPtr() + begin + count);
      check(MatSetValues(matrix_, 1, &r, count, cols.data(), A.valuePtr() + begin, INSERT_VALUES), "MatSetValues");
    }
    check(MatAssemblyBegin(matrix_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(matrix_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    check(KSPSetOperators(ksp_, matrix_, matrix_), "KSPSetOperators");
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
      check(PetscOptionsLeftGet(nullptr, &count, &names, &values), "PetscOptionsLeftGet");
      std::string unused;
      for (PetscInt i = 0; i < count; ++i)
        if (std::string(names[i]) != "no_signal_handler") unused += " -" + std::string(names[i]);
      check(PetscOptionsLeftRestore(nullptr, &count, &names, &values), "PetscOptionsLeftRestore");
      if (!unused.empty())
        return LinearSolverStatus::failure("petsc: option(s)" + unused + " in '" + options_ +
                                           "' were never used: misspelled, or not for this KSP/PC");
    }
    return LinearSolverStatus::success();
  }

  LinearSolverStatus solve(const Vector& b, Vector& x) override {
    PetscScalar* bb = nullptr;
    check(VecGetArray(b_, &bb), "VecGetArray");
    for (PetscInt r = first_; r < end_; ++r) bb[r - first_] = b[r];
    check(VecRestoreArray(b_, &bb), "VecRestoreArray");
    check(KSPSolve(ksp_, b_, x_), "KSPSolve");
    KSPConvergedReason reason;
    check(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason");
    PetscInt iterations = 0;
    check(KSPGetIterationNumber(ksp_, &iterations), "KSPGetIterationNumber");
    iterations_ = static_cast<int>(iterations);
    if (reason < 0)
      return LinearSolverStatus::failure(std::string("petsc: KSP diverged (") + KSPConvergedReasons[reason] +
                                         ") after " + std::to_string(iterations) + " iterations");
    check(VecScatterBegin(gather_, x_, all_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(gather_, x_, all_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    const PetscScalar* xa = nullptr;
    check(VecGetArrayRead(all_, &xa), "VecGetArrayRead");
    x = Eigen::Map<const Vector>(xa, b.size());
    check(VecRestoreArrayRead(all_, &xa), "VecRestoreArrayRead");
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
      check(VecDuplicate(x_, &vectors[k]), "VecDuplicate");
      PetscScalar* v = nullptr;
      check(VecGetArray(vectors[k], &v), "VecGetArray");
      for (PetscInt r = first_; r < end_; ++r) v[r - first_] = near_null_space_[k][r];
      check(VecRestoreArray(vectors[k], &v), "VecRestoreArray");
    }
    MatNullSpace space = nullptr;
    check(MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_FALSE, static_cast<PetscInt>(vectors.size()), vectors.data(),
                             &space),
          "MatNullSpaceCreate");
    check(MatSetNearNullSpace(matrix_, space), "MatSetNearNullSpace");
    check(MatNullSpaceDestroy(&space), "MatNullSpaceDestroy");
    for (Vec& v : vectors) check(VecDestroy(&v), "VecDestroy");
  }

  std::vector<Vector> near_null_space_;
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

std::unique_ptr<LinearSolver> make_petsc_solver(const std::string& options, double relative_tolerance) {
  return std::make_unique<PetscSolver>(options, relative_tolerance);
}

}  // namespace kerf
