#pragma once
// A = c_M M + c_K K on the free dofs, row by row, read from the whole-dof
// matrices' values in K's pattern: what a backend that copies the matrix into
// its own storage (PETSc) takes, so that kerf forms no A_ff beside the
// backend's copy (16 bytes a nonzero: about a quarter of a static run's peak).
#include <vector>

#include "solvers/linear_solver.h"
#include "solvers/sparse_assembly.h"

namespace kerf {

class FreeSystemRows final : public MatrixRows {
 public:
  /// K's values `stiffness` and the consistent mass's `mass` (or null) in
  /// `pattern`'s positions; `lumped_mass` (whole-dof, or null) on the diagonal.
  FreeSystemRows(const SparseMatrix& pattern, const FreeDofs& free, double stiffness_coefficient,
                 const double* stiffness, double mass_coefficient, const double* mass, const Vector* lumped_mass)
      : pattern_(pattern), free_(free), ck_(stiffness_coefficient), cm_(mass_coefficient), k_(stiffness),
        m_(mass), lumped_(lumped_mass) {}
  Index size() const override { return free_.free_count(); }
  void row(Index r, std::vector<Index>& columns, std::vector<double>& values) const override;

 private:
  const SparseMatrix& pattern_;
  const FreeDofs& free_;
  double ck_, cm_;
  const double* k_;
  const double* m_;
  const Vector* lumped_;
};

}  // namespace kerf
