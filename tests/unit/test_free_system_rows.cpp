// A's rows read straight from K and M (what PETSc takes) are the rows of the
// A_ff kerf forms for the other backends, value for value: with constrained
// dofs inside and at the ends of the numbering, with a consistent and with a
// lumped mass, and with K alone.
#include <gtest/gtest.h>

#include <random>

#include "solvers/free_system_rows.h"
#include "solvers/sparse_assembly.h"

namespace kerf {
namespace {

/// A symmetric matrix of n rows with a full diagonal and random couplings.
SparseMatrix random_symmetric(Index n, std::mt19937& random) {
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::bernoulli_distribution coupled(0.3);
  std::vector<Eigen::Triplet<double>> entries;
  for (Index i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 4.0 + value(random));
    for (Index j = i + 1; j < n; ++j)
      if (coupled(random)) {
        const double a = value(random);
        entries.emplace_back(i, j, a);
        entries.emplace_back(j, i, a);
      }
  }
  SparseMatrix m(n, n);
  m.setFromTriplets(entries.begin(), entries.end());
  m.makeCompressed();
  return m;
}

/// Every row of `rows` against the same row of `formed`.
void expect_same_rows(const MatrixRows& rows, const SparseMatrix& formed, const std::string& what) {
  ASSERT_EQ(rows.size(), formed.rows()) << what;
  std::vector<Index> columns;
  std::vector<double> values;
  for (Index r = 0; r < rows.size(); ++r) {
    rows.row(r, columns, values);
    const Index begin = formed.outerIndexPtr()[r], end = formed.outerIndexPtr()[r + 1];
    ASSERT_EQ(static_cast<Index>(columns.size()), end - begin) << what << ", row " << r;
    for (Index p = begin; p < end; ++p) {
      EXPECT_EQ(columns[p - begin], formed.innerIndexPtr()[p]) << what << ", row " << r;
      EXPECT_EQ(values[p - begin], formed.valuePtr()[p]) << what << ", row " << r;
    }
  }
}

TEST(FreeSystemRows, AreTheRowsOfTheFormedFreeMatrix) {
  std::mt19937 random(7);
  const Index n = 14;
  const SparseMatrix K = random_symmetric(n, random);
  SparseMatrix M = K;  // another matrix in K's pattern
  for (Index p = 0; p < M.nonZeros(); ++p) M.valuePtr()[p] = 0.1 * (p % 5) + 0.3;
  Vector lumped(n);
  for (Index i = 0; i < n; ++i) lumped[i] = 1.0 + 0.25 * i;
  const std::vector<DirichletDof> constrained{{0, 0.0}, {5, 0.1}, {6, 0.0}, {13, -0.2}};
  FreeDofs free(n, constrained);
  free.prepare_matrix(K);
  const double ck = 0.7, cm = 3.5;
  const double* k = K.valuePtr();
  const double* m = M.valuePtr();

  free.restrict_values_with([=](Index p) { return ck * k[p]; });
  expect_same_rows(FreeSystemRows(K, free, ck, k, 0.0, nullptr, nullptr), free.restricted(), "K alone");

  free.restrict_values_with([=](Index p) { return ck * k[p] + cm * m[p]; });
  expect_same_rows(FreeSystemRows(K, free, ck, k, cm, m, nullptr), free.restricted(), "consistent mass");

  free.restrict_values_with([=](Index p) { return ck * k[p]; });
  free.add_to_diagonal(cm, lumped);
  expect_same_rows(FreeSystemRows(K, free, ck, k, cm, nullptr, &lumped), free.restricted(), "lumped mass");
}

}  // namespace
}  // namespace kerf
