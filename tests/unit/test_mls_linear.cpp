// The linear MLS kernel (mls_linear.h) against the general one: the same
// shape functions, gradients and condition numbers on graded node sets in 2D
// and 3D, with a cut's factors on the weights, and the same refusals (nodes
// on one plane, a point no support covers); its Jacobi eigenvalues against
// Eigen's on matrices from well to badly conditioned.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

#include "discretization/meshless/mls_linear.h"

namespace kerf {
namespace {

TEST(SymmetricEigenvalues, MatchEigensSolverFromWellToBadlyConditioned) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int m = 2; m <= 4; ++m)
    for (double smallest : {1.0, 1e-3, 1e-8, 1e-12}) {
      for (int trial = 0; trial < 50; ++trial) {
        // Q diag(lambda) Q^T with eigenvalues from 1 down to `smallest`.
        const Eigen::MatrixXd q = Eigen::MatrixXd::NullaryExpr(m, m, [&] { return u(random); }).householderQr()
                                      .householderQ();
        Eigen::VectorXd lambda(m);
        for (int i = 0; i < m; ++i) lambda[i] = std::pow(smallest, static_cast<double>(i) / (m - 1));
        const Eigen::MatrixXd a = q * lambda.asDiagonal() * q.transpose();
        double copy[4][4] = {}, ours[4];
        for (int i = 0; i < m; ++i)
          for (int j = 0; j < m; ++j) copy[i][j] = 0.5 * (a(i, j) + a(j, i));
        symmetric_eigenvalues(m, copy, ours);
        const Eigen::VectorXd reference = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a).eigenvalues();
        for (int i = 0; i < m; ++i)
          ASSERT_NEAR(ours[i], reference[i], 1e-14) << "m " << m << ", smallest " << smallest << ", eigenvalue " << i;
        // What the condition number is built from: the smallest one, relative to
        // itself, as well as the matrix's own rounding (1e-16 of the largest) allows.
        if (smallest >= 1e-8) {
          EXPECT_NEAR(ours[0] / reference[0], 1.0, 1e-15 / smallest + 1e-12) << "m " << m << ", smallest " << smallest;
        }
      }
    }
}

/// A graded, jittered lattice over [0, 1]^dim: nodes crowd towards x = 0
/// (x = s^2), each moved by a quarter of its local spacing; supports 2.3
/// local spacings (the largest of the directions').
struct Cloud {
  std::vector<Vec3> nodes;
  std::vector<double> support;
};
Cloud graded_cloud(int dim, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.25, 0.25);
  const int n = dim == 3 ? 10 : 24;
  const double h = 1.0 / n;
  Cloud c;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= (dim == 3 ? n : 0); ++k) {
        const double s = i * h, spacing_x = std::max(2.0 * s * h, h * h), spacing = std::max(2.0 * s * h, h);
        c.nodes.emplace_back(s * s + jitter(random) * spacing_x, (j + jitter(random)) * h,
                             dim == 3 ? (k + jitter(random)) * h : 0.0);
        c.support.push_back(2.3 * spacing);
      }
  return c;
}

struct Sample {
  std::vector<Vec3> near;
  std::vector<WeightWithGradient> lean;
  std::vector<WeightValue> full;
  double scale = 0.0;
};
/// The nodes covering x, their weights times a random cut factor in (0, 1]
/// with a random gradient where `cut`.
Sample sample_at(const Cloud& c, const Vec3& x, bool cut, std::mt19937& random) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Sample s;
  for (std::size_t I = 0; I < c.nodes.size(); ++I) {
    if ((x - c.nodes[I]).norm() >= c.support[I]) continue;
    WeightWithGradient w = quartic_weight_with_gradient(x, c.nodes[I], c.support[I]);
    if (cut && u(random) < 0.3) {
      const double g = 0.05 + 0.95 * u(random);
      const Vec3 dg = Vec3(u(random) - 0.5, u(random) - 0.5, 0.0) / c.support[I];
      w.gradient = g * w.gradient + w.value * dg;
      w.value *= g;
    }
    s.near.push_back(c.nodes[I]);
    s.lean.push_back(w);
    s.full.push_back(WeightValue{w.value, w.gradient, Mat3::Zero()});
    s.scale = std::max(s.scale, c.support[I]);
  }
  return s;
}

TEST(MlsLinear, EqualsTheGeneralKernelOnGradedCloudsWithCutFactors) {
  for (int dim : {2, 3})
    for (bool cut : {false, true}) {
      const Cloud cloud = graded_cloud(dim, 5 + dim);
      std::mt19937 random(17);
      std::uniform_real_distribution<double> u(0.02, 0.98);
      int compared = 0;
      for (int p = 0; p < 200; ++p) {
        const double r = u(random);
        const Vec3 x(r * r, u(random), dim == 3 ? u(random) : 0.0);  // as graded as the nodes
        const Sample s = sample_at(cloud, x, cut, random);
        MlsShape general, linear;
        const bool general_ok =
            mls_shape_functions(dim, MlsBasis::linear, x, s.near, s.full, s.scale, false, general);
        const bool linear_ok = mls_linear_shape_functions(dim, x, s.near, s.lean, s.scale, linear);
        ASSERT_EQ(general_ok, linear_ok) << dim << "D, point " << p;
        if (!general_ok) continue;
        ++compared;
        // Both solve the same system, by different factorizations: they agree to its condition times round-off.
        const double kappa = general.condition, tolerance = 1e-15 * kappa;
        EXPECT_NEAR(linear.condition / kappa, 1.0, 1e-9) << dim << "D, point " << p;
        ASSERT_EQ(linear.value.size(), s.near.size());
        EXPECT_TRUE(linear.hessian.empty());
        for (std::size_t k = 0; k < s.near.size(); ++k) {
          EXPECT_NEAR(linear.value[k], general.value[k], tolerance) << dim << "D, point " << p << ", node " << k;
          for (int i = 0; i < 3; ++i) {
            const double g = general.gradient[k][i];
            EXPECT_NEAR(linear.gradient[k][i], g, tolerance * (1.0 + std::abs(g))) << dim << "D, point " << p;
          }
        }
      }
      EXPECT_GT(compared, 150) << dim << "D";
    }
}

TEST(MlsLinear, RefusesWhatTheGeneralKernelRefuses) {
  // 3D nodes on one plane: the linear basis cannot tell z apart.
  std::vector<Vec3> plane;
  std::vector<WeightWithGradient> lean;
  std::vector<WeightValue> full;
  const Vec3 x(0.5, 0.5, 0.0);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      plane.emplace_back(0.25 * i, 0.25 * j, 0.0);
      lean.push_back(quartic_weight_with_gradient(x, plane.back(), 0.8));
      full.push_back(quartic_weight(x, plane.back(), 0.8, false));
    }
  MlsShape general, linear;
  EXPECT_FALSE(mls_shape_functions(3, MlsBasis::linear, x, plane, full, 0.8, false, general));
  EXPECT_FALSE(mls_linear_shape_functions(3, x, plane, lean, 0.8, linear));
  EXPECT_GT(linear.condition, 1e12);
  // No node at all.
  EXPECT_FALSE(mls_linear_shape_functions(3, x, {}, {}, 1.0, linear));
  EXPECT_TRUE(std::isinf(linear.condition));
}

}  // namespace
}  // namespace kerf
