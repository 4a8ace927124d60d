// The critical step's Lanczos (solvers/largest_eigenvalue.h) against the
// eigenvalues of a small generalized problem computed densely.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "solvers/largest_eigenvalue.h"

namespace kerf {
namespace {

/// A chain of springs of unequal stiffness between unequal masses, its first
/// mass held: its largest eigenvalues lie close together, as a lattice's do.
struct Chain {
  Eigen::MatrixXd K;
  Vector mass;
  FreeDofs free;
  explicit Chain(Index n) : K(Eigen::MatrixXd::Zero(n, n)), mass(n), free(n, {{0, 0.0}}) {
    for (Index i = 0; i + 1 < n; ++i) {
      const double k = 1.0 + 0.3 * std::sin(1.7 * static_cast<double>(i));
      K(i, i) += k, K(i + 1, i + 1) += k, K(i, i + 1) -= k, K(i + 1, i) -= k;
    }
    for (Index i = 0; i < n; ++i) mass[i] = 1.0 + 0.2 * std::cos(0.9 * static_cast<double>(i));
  }
  StiffnessTimes times() const {
    return [this](const Vector& x, Vector& y) { y = K * x; };
  }
  /// The largest eigenvalue of M^-1 K on the free dofs, densely.
  double largest() const {
    const Index n = mass.size() - 1;
    const Vector s = mass.tail(n).cwiseSqrt().cwiseInverse();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(s.asDiagonal() * K.bottomRightCorner(n, n) * s.asDiagonal());
    return eig.eigenvalues().maxCoeff();
  }
};

TEST(LargestEigenvalue, BoundsTheLargestEigenvalueFromAboveAndItsRitzValueFromBelow) {
  const Chain chain(60);
  LanczosOptions options;
  options.start_entry = [](Index dof) { return 1.0 + 0.01 * static_cast<double>(dof); };
  const EigenvalueBound bound = largest_eigenvalue(chain.times(), chain.mass, chain.free, options);
  const double exact = chain.largest();
  EXPECT_LE(bound.ritz_value, exact * (1.0 + 1e-12));
  EXPECT_GE(bound.upper_bound, exact * (1.0 - 1e-12));
  EXPECT_LT(bound.upper_bound, exact * (1.0 + 1e-5));
}

// A previous estimate's Ritz vector comes out with either sign (rounding
// chooses; a run on 2 ranks had it negated). An estimate started from it
// must not depend on which: on 2 ranks the re-estimate after a growing cut
// differed by 2.5e-4 from the serial run's when it did.
TEST(LargestEigenvalue, AnEstimateStartedFromARitzVectorDoesNotDependOnItsSign) {
  const Chain chain(80);
  LanczosOptions first;
  first.tolerance = 1e-1;  // a rough mode, as a re-estimate gets
  first.start_entry = [](Index dof) { return std::cos(0.37 * static_cast<double>(dof)); };
  const EigenvalueBound rough = largest_eigenvalue(chain.times(), chain.mass, chain.free, first);
  const Vector negated = -rough.ritz_vector;
  LanczosOptions again = first;
  again.tolerance = 1e-2;
  again.start = &rough.ritz_vector;
  const EigenvalueBound plus = largest_eigenvalue(chain.times(), chain.mass, chain.free, again);
  again.start = &negated;
  const EigenvalueBound minus = largest_eigenvalue(chain.times(), chain.mass, chain.free, again);
  EXPECT_EQ(plus.iterations, minus.iterations);
  EXPECT_NEAR(plus.upper_bound, minus.upper_bound, 1e-12 * plus.upper_bound);
  EXPECT_NEAR(plus.ritz_value, minus.ritz_value, 1e-12 * plus.ritz_value);
}

}  // namespace
}  // namespace kerf
