#include "solvers/free_system_rows.h"

namespace kerf {

void FreeSystemRows::row(Index r, std::vector<Index>& columns, std::vector<double>& values) const {
  columns.clear();
  values.clear();
  const Index dof = free_.free_dofs()[r];
  const Index* column = pattern_.innerIndexPtr();
  for (Index p = pattern_.outerIndexPtr()[dof]; p < pattern_.outerIndexPtr()[dof + 1]; ++p) {
    const Index j = free_.free_index(column[p]);
    if (j < 0) continue;  // a constrained column: not in A_ff
    double a = ck_ != 0.0 ? ck_ * k_[p] : 0.0;
    if (m_) a += cm_ * m_[p];
    if (lumped_ && j == r) a += cm_ * (*lumped_)[dof];
    columns.push_back(j);
    values.push_back(a);
  }
}

}  // namespace kerf
