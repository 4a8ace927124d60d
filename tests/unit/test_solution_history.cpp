// The start a preconditioned CG takes from the last solutions: the Galerkin
// projection onto their span is the A-norm-best point of it (the error is
// A-orthogonal to every kept solution), whatever repeats or degenerates in
// the history, and only the last `capacity` solutions of the current length count.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "core/check.h"
#include "solvers/solution_history.h"

namespace kerf {
namespace {

/// A 2D Laplacian on an m x m grid plus a small shift: sparse, SPD, not well conditioned.
SparseMatrix laplacian(Index m) {
  std::vector<Eigen::Triplet<double, Index>> entries;
  auto at = [m](Index i, Index j) { return i * m + j; };
  for (Index i = 0; i < m; ++i)
    for (Index j = 0; j < m; ++j) {
      entries.emplace_back(at(i, j), at(i, j), 4.0 + 1e-3);
      if (i > 0) entries.emplace_back(at(i, j), at(i - 1, j), -1.0);
      if (i + 1 < m) entries.emplace_back(at(i, j), at(i + 1, j), -1.0);
      if (j > 0) entries.emplace_back(at(i, j), at(i, j - 1), -1.0);
      if (j + 1 < m) entries.emplace_back(at(i, j), at(i, j + 1), -1.0);
    }
  SparseMatrix A(m * m, m * m);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

double energy_norm(const SparseMatrix& A, const Vector& e) { return std::sqrt(e.dot(A * e)); }

struct System {
  SparseMatrix A = laplacian(15);
  Vector exact = Vector::Random(225);
  Vector b = A * exact;
};

TEST(SolutionHistory, NothingKeptStartsFromZero) {
  System s;
  SolutionHistory history(4);
  Vector x0, r0;
  history.start(s.A, s.b, x0, r0);
  EXPECT_TRUE(x0.isZero());
  EXPECT_EQ(r0, s.b);
}

TEST(SolutionHistory, StartIsTheSolutionWhenTheSpanHoldsIt) {
  System s;
  SolutionHistory history(4);
  const Vector noise = Vector::Random(225);
  history.remember(Vector::Random(225));
  history.remember(0.5 * s.exact + noise);
  history.remember(Vector::Random(225));
  history.remember(0.5 * s.exact - noise);  // the solution is the sum of two of them
  Vector x0, r0;
  history.start(s.A, s.b, x0, r0);
  EXPECT_LT((x0 - s.exact).norm(), 1e-10 * s.exact.norm());
  EXPECT_LT(r0.norm(), 1e-10 * s.b.norm());
}

// Partly filled, full, and after older solutions were dropped; at capacity 8
// (the implicit steps') every column of the pass over A is in use.
TEST(SolutionHistory, StartIsTheBestPointOfTheSpanInTheEnergyNorm) {
  for (const auto& [capacity, remembered] : {std::pair{5, 5}, {8, 3}, {8, 8}, {8, 11}}) {
    System s;
    SolutionHistory history(capacity);
    std::vector<Vector> kept;
    for (int i = 0; i < remembered; ++i) {
      kept.push_back(s.exact + 2.0 * Vector::Random(225));
      history.remember(kept.back());
    }
    kept.erase(kept.begin(), kept.end() - std::min(capacity, remembered));
    Vector x0, r0;
    history.start(s.A, s.b, x0, r0);
    const std::string name = std::to_string(remembered) + " of " + std::to_string(capacity);
    EXPECT_LT((r0 - (s.b - s.A * x0)).norm(), 1e-12 * s.b.norm()) << name;
    // Galerkin: the residual is orthogonal to every kept solution.
    for (const Vector& v : kept) EXPECT_LT(std::abs(v.dot(r0)), 1e-10 * v.norm() * s.b.norm()) << name;
    const double error = energy_norm(s.A, x0 - s.exact);
    EXPECT_LT(error, energy_norm(s.A, s.exact)) << name;  // better than zero
    for (const Vector& v : kept) {  // and than the best multiple of any one of them
      const double scale = v.dot(s.b) / v.dot(s.A * v);
      EXPECT_LT(error, energy_norm(s.A, scale * v - s.exact)) << name;
    }
  }
}

TEST(SolutionHistory, RepeatedAndZeroSolutionsAddNothing) {
  System s;
  const Vector v = s.exact + Vector::Random(225), w = Vector::Random(225);
  SolutionHistory clean(2), degenerate(6);
  clean.remember(v);
  clean.remember(w);
  degenerate.remember(v);
  degenerate.remember(Vector::Zero(225));
  degenerate.remember(2.0 * v);
  degenerate.remember(w);
  degenerate.remember(v + 1e-14 * Vector::Random(225));
  degenerate.remember(-w);
  Vector x_clean, r_clean, x0, r0;
  clean.start(s.A, s.b, x_clean, r_clean);
  degenerate.start(s.A, s.b, x0, r0);
  ASSERT_TRUE(x0.allFinite());
  EXPECT_LT((x0 - x_clean).norm(), 1e-8 * x_clean.norm());
  EXPECT_LT((r0 - r_clean).norm(), 1e-8 * s.b.norm());
}

// An exact tangent under compression can be indefinite: a kept solution along
// which A is negative is left out, not inverted into the start.
TEST(SolutionHistory, SolutionsAlongWhichANotPositiveAddNothing) {
  SparseMatrix A(4, 4);
  for (Index i = 0; i < 4; ++i) A.insert(i, i) = i == 0 ? -1.0 : i;
  const Vector b = Vector::Ones(4), v = Vector(Eigen::Vector4d(0.0, 1.0, 1.0, 1.0));
  SolutionHistory history(2);
  history.remember(Vector(Eigen::Vector4d(1.0, 0.0, 0.0, 0.0)));
  history.remember(v);
  Vector x0, r0;
  history.start(A, b, x0, r0);
  EXPECT_LT((x0 - v.dot(b) / v.dot(A * v) * v).norm(), 1e-15);
}

TEST(SolutionHistory, KeepsTheLastSolutionsOfTheCurrentLength) {
  System s;
  SolutionHistory history(3);
  Vector x0, r0;
  history.remember(s.exact);  // dropped by the three after it
  for (int i = 0; i < 3; ++i) history.remember(Vector::Random(225));
  EXPECT_EQ(history.size(), 3);
  history.start(s.A, s.b, x0, r0);
  EXPECT_GT((x0 - s.exact).norm(), 1e-2 * s.exact.norm());
  history.remember(s.exact);
  history.start(s.A, s.b, x0, r0);
  EXPECT_LT((x0 - s.exact).norm(), 1e-10 * s.exact.norm());
  history.remember(Vector::Ones(10));  // the dofs changed: the others are forgotten
  EXPECT_EQ(history.size(), 1);
  history.start(s.A, s.b, x0, r0);  // a start of the wrong length is no start
  EXPECT_TRUE(x0.isZero());
}

TEST(SolutionHistory, RefusesMoreSolutionsThanItsPassTakes) {
  EXPECT_NO_THROW(SolutionHistory(SolutionHistory::max_capacity));
  EXPECT_THROW(SolutionHistory(SolutionHistory::max_capacity + 1), Error);
  EXPECT_THROW(SolutionHistory(-1), Error);
}

}  // namespace
}  // namespace kerf
