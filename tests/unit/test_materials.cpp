// Every material: stress is the derivative of the energy, the tangent is the
// derivative of the stress (central finite differences), objectivity, rest state.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <type_traits>

#include "problem/material.h"

namespace kerf {
namespace {

const MaterialModel all_models[] = {MaterialModel::linear, MaterialModel::corotational, MaterialModel::stvk,
                                    MaterialModel::neohookean, MaterialModel::neohookean_uncoupled};

Mat3 sample_deformation(int seed, double amplitude) {
  std::srand(seed);
  return Mat3::Identity() + amplitude * Mat3::Random();
}

/// d value(F) / dF by central differences, for a scalar (a 3x3 result) or a
/// stress (a 9x9 result laid out as dP/dF: column k + 3l along F(k, l)).
template <class Function>
auto central_differences(Function&& value, const Mat3& F) {
  const double h = 1e-6;
  using Value = decltype(value(F));
  Eigen::Matrix<double, std::is_same_v<Value, double> ? 3 : 9, std::is_same_v<Value, double> ? 3 : 9> d;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      Mat3 Fp = F, Fm = F;
      Fp(k, l) += h;
      Fm(k, l) -= h;
      if constexpr (std::is_same_v<Value, double>) {
        d(k, l) = (value(Fp) - value(Fm)) / (2 * h);
      } else {
        const Mat3 dP = (value(Fp) - value(Fm)) / (2 * h);
        d.col(k + 3 * l) = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(dP.data());
      }
    }
  return d;
}

class MaterialTest : public ::testing::TestWithParam<MaterialModel> {};

TEST_P(MaterialTest, StressIsEnergyDerivative) {
  MaterialLaw law(GetParam(), 1.0e6, 0.3);
  for (int seed = 1; seed <= 5; ++seed) {
    Mat3 F = sample_deformation(seed, 0.2);
    const Mat3 P = law.stress(F);
    const Mat3 numeric = central_differences([&](const Mat3& G) { return law.energy(G); }, F);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(P(i, j), numeric(i, j), 1e-6 * P.norm()) << to_string(GetParam()) << " seed " << seed;
  }
}

TEST_P(MaterialTest, TangentIsStressDerivative) {
  MaterialLaw law(GetParam(), 1.0e6, 0.3);
  for (int seed = 1; seed <= 5; ++seed) {
    Mat3 F = sample_deformation(seed, 0.2);
    Mat3 P;
    Mat9 C;
    law.stress_and_tangent(F, P, C);
    EXPECT_LT((P - law.stress(F)).norm(), 1e-12 * P.norm());
    const Mat9 numeric = central_differences([&](const Mat3& G) { return law.stress(G); }, F);
    EXPECT_LT((C - numeric).norm(), 1e-6 * C.norm()) << to_string(GetParam()) << " seed " << seed;
    // Hyperelastic tangents are symmetric (major symmetry).
    EXPECT_LT((C - C.transpose()).norm(), 1e-8 * C.norm());
  }
}

// The averaged-nodal-pressure cell moves k/2 m^2 (k: lambda or the bulk
// modulus) to the nodes: what stays in the cell must not hold k at all (or it still locks), and its
// stress and tangent must be the derivatives of what it says they are.
TEST_P(MaterialTest, BulkTermHoldsAllOfLambdaAndItsDerivativesAreConsistent) {
  const double mu = Lame::from_young_poisson(1.0e6, 0.3).mu, poisson = 0.499;
  const MaterialLaw law(GetParam(), 1.0e6, 0.3), stiff(GetParam(), 2.0 * mu * (1.0 + poisson), poisson);
  ASSERT_GT(stiff.lame().lambda, 50.0 * law.lame().lambda);
  for (int seed = 1; seed <= 5; ++seed) {
    const Mat3 F = sample_deformation(seed, 0.2);
    const double averaged = law.bulk_measure(F).value + 0.05;
    // Equal to round-off of what was taken away.
    EXPECT_NEAR(law.energy_without_bulk(F), stiff.energy_without_bulk(F), 1e-12 * stiff.energy(F))
        << to_string(GetParam()) << " seed " << seed;
    Mat3 P;
    Mat9 C;
    law.averaged_bulk_stress_and_tangent(F, law.bulk_measure(F), averaged, P, C);
    EXPECT_LT((P - law.averaged_bulk_stress(F, law.bulk_measure(F), averaged)).norm(), 1e-12 * P.norm());
    const Mat3 dm = central_differences([&](const Mat3& G) { return law.bulk_measure(G).value; }, F);
    EXPECT_LT((law.bulk_measure(F).gradient - dm).cwiseAbs().maxCoeff(), 1e-8);
    // The cell's share: W - k/2 m^2, whose stress is the averaged one at averaged = 0.
    const Mat3 share = central_differences([&](const Mat3& G) { return law.energy_without_bulk(G); }, F);
    EXPECT_LT((law.averaged_bulk_stress(F, law.bulk_measure(F), 0.0) - share).cwiseAbs().maxCoeff(), 1e-6 * P.norm());
    const Mat9 numeric = central_differences(
        [&](const Mat3& G) { return law.averaged_bulk_stress(G, law.bulk_measure(G), averaged); }, F);
    EXPECT_LT((C - numeric).norm(), 1e-6 * C.norm()) << to_string(GetParam()) << " seed " << seed;
  }
}

TEST_P(MaterialTest, RestStateIsStressFree) {
  MaterialLaw law(GetParam(), 1.0e6, 0.3);
  EXPECT_LT(law.stress(Mat3::Identity()).norm(), 1e-9);
  EXPECT_NEAR(law.energy(Mat3::Identity()), 0.0, 1e-12);
}

// Against Hooke's law written out here: sigma = lambda tr(eps) I + 2 mu eps,
// eps = sym(F - I), with lambda and mu from E = 1 MPa, nu = 0.3 by hand.
TEST_P(MaterialTest, SmallStrainMatchesHookesLaw) {
  MaterialLaw law(GetParam(), 1.0e6, 0.3);
  const double lambda = 1.0e6 * 0.3 / (1.3 * 0.4), mu = 1.0e6 / 2.6;
  Mat3 F = sample_deformation(7, 1e-6);
  const Mat3 eps = 0.5 * (F + F.transpose()) - Mat3::Identity();
  const Mat3 hooke = lambda * eps.trace() * Mat3::Identity() + 2.0 * mu * eps;
  EXPECT_LT((law.stress(F) - hooke).norm(), 1e-5 * hooke.norm()) << to_string(GetParam());
}

TEST(Material, NonlinearModelsAreObjective) {
  Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  Mat3 F = sample_deformation(3, 0.2);
  for (MaterialModel m : {MaterialModel::corotational, MaterialModel::stvk, MaterialModel::neohookean,
                          MaterialModel::neohookean_uncoupled}) {
    MaterialLaw law(m, 1.0e6, 0.3);
    EXPECT_NEAR(law.energy(R * F), law.energy(F), 1e-10 * law.energy(F)) << to_string(m);
    EXPECT_LT((law.stress(R * F) - R * law.stress(F)).norm(), 1e-9 * law.stress(F).norm()) << to_string(m);
  }
}

// solve.tangent: definite. Under strong compression the exact tangents of the
// nonlinear models have negative eigenvalues; the definite one has none, and
// where the exact one is already positive semidefinite (a stretch) it is the exact one.
TEST(Material, DefiniteTangentIsTheExactOneWhereThatIsSemidefinite) {
  for (MaterialModel m : {MaterialModel::corotational, MaterialModel::stvk, MaterialModel::neohookean,
                          MaterialModel::neohookean_uncoupled}) {
    const Material material{m, 1.0e6, 0.3, 1000.0, 0.0, 0.0};
    const MaterialLaw exact(material), definite(material, true);
    Mat3 P, P_definite;
    Mat9 C, C_definite;
    const Mat3 squeezed = Eigen::AngleAxisd(0.4, Vec3(1, 1, 0).normalized()).toRotationMatrix() *
                          Vec3(0.45, 0.5, 1.1).asDiagonal();
    exact.stress_and_tangent(squeezed, P, C);
    definite.stress_and_tangent(squeezed, P_definite, C_definite);
    const Mat9 symmetric = 0.5 * (C + C.transpose());
    EXPECT_LT(Eigen::SelfAdjointEigenSolver<Mat9>(symmetric).eigenvalues().minCoeff(), -1e-3 * C.norm()) << to_string(m);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Mat9>(C_definite).eigenvalues().minCoeff(), -1e-9 * C.norm()) << to_string(m);
    EXPECT_EQ(P, P_definite);
    const Mat3 stretched = Vec3(1.1, 1.05, 1.02).asDiagonal();
    exact.stress_and_tangent(stretched, P, C);
    definite.stress_and_tangent(stretched, P_definite, C_definite);
    EXPECT_LT((C_definite - 0.5 * (C + C.transpose())).norm(), 1e-12 * C.norm()) << to_string(m);
  }
}

TEST(Material, PolarRotationIsTheRotationOfTheSvd) {
  for (int seed = 1; seed <= 50; ++seed) {
    // Large stretches and rotations, and (seeds over 40) nearly flat or inverted F.
    Mat3 R0 = Eigen::AngleAxisd(0.3 * seed, Vec3(1, seed % 3, 2).normalized()).toRotationMatrix();
    Mat3 F = R0 * sample_deformation(seed, 0.6);
    if (seed > 40) F.col(seed % 3) *= seed % 2 ? 1e-6 : -0.5;
    Mat3 R = polar_rotation(F);
    EXPECT_LT((R.transpose() * R - Mat3::Identity()).norm(), 1e-12) << seed;
    EXPECT_NEAR(R.determinant(), 1.0, 1e-12) << seed;
    Eigen::JacobiSVD<Mat3> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Mat3 U = svd.matrixU(), V = svd.matrixV();
    if (U.determinant() < 0) U.col(2) *= -1;
    if (V.determinant() < 0) V.col(2) *= -1;
    EXPECT_LT((R - U * V.transpose()).norm(), 1e-10) << seed;
    // S = R^T F is symmetric.
    Mat3 S = R.transpose() * F;
    EXPECT_LT((S - S.transpose()).norm(), 1e-10 * F.norm()) << seed;
  }
}

// The Newton iteration stops once its step is below 1e-8: R must still be a
// rotation, and R^T F symmetric, to round-off, from F a rotation to F with
// large stretches (the step's bound is quadratic: a looser stop shows here).
TEST(Material, PolarRotationIsARotationToRoundOffAtEveryStrain) {
  for (double strain : {0.0, 1e-12, 1e-9, 1e-7, 1e-5, 1e-3, 1e-2, 0.1, 0.5})
    for (int seed = 1; seed <= 10; ++seed) {
      const Mat3 turn = Eigen::AngleAxisd(0.5 * seed, Vec3(1, seed % 3, 2).normalized()).toRotationMatrix();
      std::srand(seed);
      const Mat3 F = turn * (Mat3::Identity() + strain * Mat3::Random());
      const Mat3 R = polar_rotation(F);
      EXPECT_LT((R.transpose() * R - Mat3::Identity()).norm(), 2e-15) << strain << ", seed " << seed;
      const Mat3 S = R.transpose() * F;
      EXPECT_LT((S - S.transpose()).norm(), 2e-15 * F.norm()) << strain << ", seed " << seed;
    }
}

// The corotational tangent is written in closed form from R and S; here it is
// checked against the SVD's directional derivative of R (written out below, as
// the textbooks do: dR = U W V^T, W_ij = (M_ij - M_ji) / (s_i + s_j), M = U^T dF V)
// and against central differences, on F = Q (I + 0.6 X) with Q a rotation of up
// to 2.7 rad and X's entries uniform in [-1, 1] (large, unequal stretches and
// shears), and (seeds over 40) on the nearly flat or inverted F that take the SVD path.
TEST(Material, CorotationalTangentUnderLargeRotationsAndStretches) {
  const MaterialLaw law(MaterialModel::corotational, 1.0e6, 0.3);
  const double lambda = law.lame().lambda, mu = law.lame().mu;
  for (int seed = 1; seed <= 50; ++seed) {
    const Mat3 turn = Eigen::AngleAxisd(0.3 * (seed % 10), Vec3(1, seed % 3, 2).normalized()).toRotationMatrix();
    Mat3 F = turn * sample_deformation(seed, 0.6);
    if (seed > 40) F.col(seed % 3) *= seed % 2 ? 1e-6 : -0.5;
    Eigen::JacobiSVD<Mat3> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Mat3 U = svd.matrixU(), V = svd.matrixV();
    Vec3 s = svd.singularValues();
    if (U.determinant() < 0) U.col(2) *= -1, s(2) *= -1;
    if (V.determinant() < 0) V.col(2) *= -1, s(2) *= -1;
    const Mat3 R = U * V.transpose();
    const double t = s.sum() - 3.0;
    const Mat9 reference = tangent_from_directions([&](const Mat3& dF) {
      const Mat3 M = U.transpose() * dF * V;
      Mat3 W = Mat3::Zero();
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          if (i != j) W(i, j) = (M(i, j) - M(j, i)) / (s(i) + s(j));
      const Mat3 dR = U * W * V.transpose();
      return Mat3(2.0 * mu * (dF - dR) + lambda * (R.transpose() * dF).trace() * R + lambda * t * dR);
    });
    Mat3 P;
    Mat9 C;
    law.stress_and_tangent(F, P, C);
    const double conditioning = s.cwiseAbs().maxCoeff() / s.cwiseAbs().minCoeff();
    EXPECT_LT((C - reference).norm(), 1e-13 * conditioning * reference.norm()) << seed;
    EXPECT_LT((P - law.stress(F)).norm(), 1e-12 * conditioning * P.norm()) << seed;
    if (seed > 40) continue;  // central differences across a flat F are meaningless
    const Mat9 numeric = central_differences([&](const Mat3& G) { return law.stress(G); }, F);
    EXPECT_LT((C - numeric).norm(), 1e-7 * C.norm()) << seed;
    // The averaged-pressure cell's tangent holds the rotation's derivative through the bulk measure's Hessian.
    const double averaged = law.bulk_measure(F).value + 0.05;
    law.averaged_bulk_stress_and_tangent(F, law.bulk_measure(F), averaged, P, C);
    const Mat9 numeric_averaged = central_differences(
        [&](const Mat3& G) { return law.averaged_bulk_stress(G, law.bulk_measure(G), averaged); }, F);
    EXPECT_LT((C - numeric_averaged).norm(), 1e-7 * C.norm()) << seed;
  }
}

TEST(Material, LameParameters) {
  Lame l = Lame::from_young_poisson(1.0e6, 0.25);
  EXPECT_NEAR(l.mu, 4.0e5, 1e-6);
  EXPECT_NEAR(l.lambda, 4.0e5, 1e-6);
}

TEST(Material, VonMisesOfUniaxialStressIsTheStress) {
  Mat3 s = Mat3::Zero();
  s(0, 0) = 250.0;
  EXPECT_NEAR(von_mises(s), 250.0, 1e-12);
  Mat3 shear = Mat3::Zero();
  shear(0, 1) = shear(1, 0) = 100.0;
  EXPECT_NEAR(von_mises(shear), std::sqrt(3.0) * 100.0, 1e-10);
}

INSTANTIATE_TEST_SUITE_P(AllModels, MaterialTest, ::testing::ValuesIn(all_models),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace kerf
