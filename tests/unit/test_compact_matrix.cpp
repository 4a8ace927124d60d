// The smoother's copy of A: single precision, node blocks where the pattern is
// made of them, scalar entries where it is not (a node with one dof held).
#include <gtest/gtest.h>

#include <random>

#include "solvers/compact_matrix.h"

namespace kerf {
namespace {

/// A symmetric matrix over `nodes` nodes of 3 dofs with random node couplings;
/// with `hold` the first dof is dropped (its row and column), so the blocks break.
SparseMatrix node_matrix(Index nodes, bool hold) {
  std::mt19937 random(11);
  std::uniform_int_distribution<Index> node(0, nodes - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double, Index>> entries;
  auto couple = [&](Index a, Index b) {
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) {
        const double v = value(random);
        entries.emplace_back(3 * a + i, 3 * b + k, v);
        entries.emplace_back(3 * b + k, 3 * a + i, v);
      }
  };
  for (Index a = 0; a < nodes; ++a) couple(a, a);
  for (int k = 0; k < 4 * nodes; ++k) couple(node(random), node(random));
  SparseMatrix A(3 * nodes, 3 * nodes);
  A.setFromTriplets(entries.begin(), entries.end());
  if (!hold) return A;
  SparseMatrix held = A.bottomRightCorner(3 * nodes - 1, 3 * nodes - 1);
  held.makeCompressed();
  return held;
}

TEST(CompactMatrix, MultipliesAsTheMatrixToSinglePrecision) {
  for (bool hold : {false, true}) {
    const SparseMatrix A = node_matrix(40, hold);
    CompactMatrix compact;
    compact.analyze(A, 3);
    EXPECT_EQ(compact.block(), hold ? 1 : 3) << "hold " << hold;
    for (int round = 0; round < 2; ++round) {  // new values, same pattern
      SparseMatrix B = A * (round + 1.0);
      compact.assign(B);
      const Vector x = Vector::LinSpaced(B.rows(), -1.0, 2.0);
      Vector y;
      compact.multiply(x, y);
      const Vector exact = B * x;
      EXPECT_LT((y - exact).cwiseAbs().maxCoeff(), 1e-6 * (B.cwiseAbs() * x.cwiseAbs()).maxCoeff())
          << "hold " << hold << ", round " << round;
    }
  }
}

}  // namespace
}  // namespace kerf
