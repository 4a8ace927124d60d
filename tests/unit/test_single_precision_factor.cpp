// The stale-factor CG preconditions with a single-precision copy of CHOLMOD's
// supernodal factor: its solve is the double one to float's round-off times
// the condition number (and not equal to it: the copy is really used), it
// follows each new factorization, and without the copy precondition() is solve().
// Its solve runs the elimination tree's two halves on two threads: the answer
// is the same on one thread, and right on a forest and on tiny matrices.
#include <cholmod.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <vector>

#include "core/run_report.h"
#include "solvers/linear_solver.h"
#include "solvers/single_precision_factor.h"

namespace kerf {
namespace {

/// A 3D Laplacian on an m^3 grid plus `shift` on the diagonal: its nested
/// dissection factor has supernodes with rows below their diagonal blocks.
SparseMatrix laplacian_3d(Index m, double shift) {
  std::vector<Eigen::Triplet<double, Index>> entries;
  auto at = [m](Index i, Index j, Index k) { return (i * m + j) * m + k; };
  for (Index i = 0; i < m; ++i)
    for (Index j = 0; j < m; ++j)
      for (Index k = 0; k < m; ++k) {
        entries.emplace_back(at(i, j, k), at(i, j, k), 6.0 + shift);
        for (Index d : {-1, 1}) {
          if (i + d >= 0 && i + d < m) entries.emplace_back(at(i, j, k), at(i + d, j, k), -1.0);
          if (j + d >= 0 && j + d < m) entries.emplace_back(at(i, j, k), at(i, j + d, k), -1.0);
          if (k + d >= 0 && k + d < m) entries.emplace_back(at(i, j, k), at(i, j, k + d), -1.0);
        }
      }
  SparseMatrix A(m * m * m, m * m * m);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

struct Factored {
  RunReport report;
  std::unique_ptr<LinearSolver> solver = make_linear_solver({}, report);
  Factored(const SparseMatrix& A, bool single) {
    if (single) solver->keep_single_precision_copy();
    EXPECT_TRUE(solver->analyze(A).ok);
    EXPECT_TRUE(solver->factorize(A).ok);
  }
};

TEST(SinglePrecisionFactor, SolvesToFloatRoundOffTimesTheConditionNumber) {
  const SparseMatrix A = laplacian_3d(14, 0.05);
  // Eigenvalues from 6 - 6 cos(pi / 15) + 0.05 = 0.18 to 12.05: condition number 67.
  const double bound = 67 * 6e-8;  // times float's unit round-off
  Factored f(A, true);
  const Vector b = Vector::Random(A.rows());
  Vector exact, approximate;
  ASSERT_TRUE(f.solver->solve(b, exact).ok);
  ASSERT_TRUE(f.solver->precondition(b, approximate).ok);
  const double error = (approximate - exact).norm() / exact.norm();
  EXPECT_LT(error, bound);
  EXPECT_GT(error, 1e-12);  // float, not the double factor
  // Its residual against A, not just against the double solve.
  EXPECT_LT((A * approximate - b).norm(), bound * b.norm());
}

TEST(SinglePrecisionFactor, FollowsEachFactorization) {
  const SparseMatrix A = laplacian_3d(10, 0.05);
  SparseMatrix B = A;
  B.diagonal().array() += 1.0;
  Factored f(A, true);
  ASSERT_TRUE(f.solver->factorize(B).ok);
  const Vector b = Vector::Random(A.rows());
  Vector x;
  ASSERT_TRUE(f.solver->precondition(b, x).ok);
  EXPECT_LT((B * x - b).norm(), 1e-5 * b.norm());
}

TEST(SinglePrecisionFactor, SameAnswerOnOneThreadAndOnTwo) {
  const SparseMatrix A = laplacian_3d(14, 0.05);
  Factored f(A, true);
  const Vector b = Vector::Random(A.rows());
  const int threads = omp_get_max_threads();
  Vector one, two;
  omp_set_num_threads(1);
  ASSERT_TRUE(f.solver->precondition(b, one).ok);
  omp_set_num_threads(2);
  ASSERT_TRUE(f.solver->precondition(b, two).ok);
  omp_set_num_threads(threads);
  EXPECT_EQ(one, two);
}

/// Two uncoupled blocks (an elimination forest, no single top chain) and matrices of one and two rows.
TEST(SinglePrecisionFactor, SolvesForestsAndTinyMatrices) {
  const SparseMatrix block = laplacian_3d(8, 0.05);
  SparseMatrix forest(2 * block.rows(), 2 * block.rows());
  std::vector<Eigen::Triplet<double, Index>> entries;
  for (Index copy = 0; copy < 2; ++copy)
    for (Index r = 0; r < block.rows(); ++r)
      for (SparseMatrix::InnerIterator it(block, r); it; ++it)
        entries.emplace_back(r + copy * block.rows(), it.col() + copy * block.rows(), it.value() * (1 + copy));
  forest.setFromTriplets(entries.begin(), entries.end());
  SparseMatrix one(1, 1), two(2, 2);
  one.insert(0, 0) = 4.0;
  two.insert(0, 0) = 2.0, two.insert(0, 1) = -1.0, two.insert(1, 0) = -1.0, two.insert(1, 1) = 2.0;
  for (const SparseMatrix* A : {&forest, &one, &two}) {
    Factored f(*A, true);
    const Vector b = Vector::Random(A->rows());
    Vector x;
    ASSERT_TRUE(f.solver->precondition(b, x).ok);
    EXPECT_LT((*A * x - b).norm(), 1e-5 * b.norm()) << A->rows() << " rows";
  }
}

// A supernodal factor written by hand whose elimination tree is not
// postordered (supernode 1 sits between supernode 0 and its parent 2): the
// two-part split assumes postorder, so this one must run as one part, in order.
TEST(SinglePrecisionFactor, SolvesAFactorWhoseTreeIsNotPostordered) {
  // L, 4 x 4, one column a supernode; below-diagonal entries L(2,0), L(3,1), L(3,2).
  Eigen::Matrix4d L = Eigen::Matrix4d::Zero();
  L.diagonal() << 2.0, 3.0, 1.5, 2.5;
  L(2, 0) = 0.5, L(3, 1) = -1.0, L(3, 2) = 0.75;
  int super[] = {0, 1, 2, 3, 4}, pi[] = {0, 2, 4, 6, 7}, px[] = {0, 2, 4, 6, 7};
  int rows[] = {0, 2, 1, 3, 2, 3, 3}, perm[] = {0, 1, 2, 3};
  double x[] = {L(0, 0), L(2, 0), L(1, 1), L(3, 1), L(2, 2), L(3, 2), L(3, 3)};
  cholmod_factor factor{};
  factor.n = 4, factor.nsuper = 4, factor.maxesize = 1;
  factor.super = super, factor.pi = pi, factor.px = px, factor.s = rows, factor.x = x, factor.Perm = perm;
  factor.is_super = 1, factor.is_ll = 1;
  factor.itype = CHOLMOD_INT, factor.xtype = CHOLMOD_REAL, factor.dtype = CHOLMOD_DOUBLE;
  SinglePrecisionFactor single;
  ASSERT_TRUE(single.copy(factor));
  const Vector b = Vector::Random(4);
  Vector solution;
  single.solve(b, solution);
  EXPECT_LT((L * L.transpose() * solution - b).norm(), 1e-5 * b.norm());
}

TEST(SinglePrecisionFactor, WithoutTheCopyPreconditionIsTheSolve) {
  const SparseMatrix A = laplacian_3d(10, 0.05);
  Factored f(A, false);
  const Vector b = Vector::Random(A.rows());
  Vector exact, x;
  ASSERT_TRUE(f.solver->solve(b, exact).ok);
  ASSERT_TRUE(f.solver->precondition(b, x).ok);
  EXPECT_EQ(x, exact);
}

}  // namespace
}  // namespace kerf
