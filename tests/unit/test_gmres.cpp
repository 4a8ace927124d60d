// Restarted right-preconditioned GMRES on unsymmetric systems it must solve:
// the true residual meets the tolerance, restarts lose nothing, a good
// preconditioner cuts the iterations, and a budget too small is reported.
#include <gtest/gtest.h>

#include <Eigen/SparseLU>

#include "core/gmres.h"

namespace kerf {
namespace {

using Matrix = Eigen::SparseMatrix<double>;  // column-major, as SparseLU takes

/// 1D convection-diffusion, central differences: unsymmetric, not normal.
Matrix convection_diffusion(Index n, double peclet) {
  std::vector<Eigen::Triplet<double>> entries;
  for (Index i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 2.0);
    if (i > 0) entries.emplace_back(i, i - 1, -1.0 - peclet);
    if (i + 1 < n) entries.emplace_back(i, i + 1, -1.0 + peclet);
  }
  Matrix A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

LinearOperator product(const Matrix& A) {
  return [&A](const Vector& x, Vector& y) { y = A * x; };
}

TEST(Gmres, SolvesAnUnsymmetricSystemToItsTrueResidual) {
  const Matrix A = convection_diffusion(120, 0.4);
  const Vector b = Vector::LinSpaced(120, -1.0, 2.0);
  Eigen::SparseLU<Matrix> lu(A);
  const Vector exact = lu.solve(b);
  const LinearOperator identity = [](const Vector& x, Vector& y) { y = x; };
  for (int restart : {10, 200}) {  // restarted many times, and not at all
    Vector x = Vector::Zero(120);
    const GmresResult r = gmres(product(A), identity, b, x, 1e-10, restart, 5000);
    EXPECT_TRUE(r.converged) << restart;
    EXPECT_LE((b - A * x).norm(), 1e-10 * b.norm() * 1.0001) << restart;
    EXPECT_LT((x - exact).norm(), 1e-6 * exact.norm()) << restart;
  }
}

TEST(Gmres, ASymmetricPartPreconditionerConvergesInAFewIterations) {
  // What kerf does with VCI: precondition A by a factorization of (A + A^T) / 2,
  // the unsymmetric part small beside it (as VCI's correction is).
  const Matrix A = convection_diffusion(300, 0.002);
  const Matrix symmetric = 0.5 * (A + Matrix(A.transpose()));
  Eigen::SparseLU<Matrix> factor(symmetric);
  const LinearOperator preconditioner = [&factor](const Vector& x, Vector& y) { y = factor.solve(x); };
  const Vector b = Vector::Ones(300);
  Vector x = Vector::Zero(300);
  const GmresResult r = gmres(product(A), preconditioner, b, x, 1e-10, 30, 90);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(r.iterations, 10);
  EXPECT_LE((b - A * x).norm(), 1e-9 * b.norm());
}

TEST(Gmres, ReportsABudgetTooSmall) {
  const Matrix A = convection_diffusion(200, 0.3);
  const Vector b = Vector::Ones(200);
  Vector x = Vector::Zero(200);
  const GmresResult r = gmres(product(A), [](const Vector& v, Vector& y) { y = v; }, b, x, 1e-12, 5, 10);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 10);
  EXPECT_GT(r.relative_residual, 1e-12);
  EXPECT_NEAR(r.relative_residual, (b - A * x).norm() / b.norm(), 1e-12);
}

TEST(Gmres, AZeroRightHandSideGivesZero) {
  const Matrix A = convection_diffusion(10, 0.1);
  Vector x = Vector::Ones(10);
  const GmresResult r = gmres(product(A), [](const Vector& v, Vector& y) { y = v; }, Vector::Zero(10), x, 1e-10, 5, 10);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(x.norm(), 0.0);
}

}  // namespace
}  // namespace kerf
