#include "problem/material.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "core/check.h"

namespace kerf {
namespace {

Mat3 sym(const Mat3& A) { return 0.5 * (A + A.transpose()); }

/// F = U diag(sigma) V^T with U, V proper rotations (an inverted F gets a negative sigma(2)).
struct RotationSvd {
  Mat3 U, V;
  Vec3 sigma;
  explicit RotationSvd(const Mat3& F) {
    Eigen::JacobiSVD<Mat3> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
    U = svd.matrixU();
    V = svd.matrixV();
    sigma = svd.singularValues();
    if (U.determinant() < 0.0) {
      U.col(2) *= -1.0;
      sigma(2) *= -1.0;
    }
    if (V.determinant() < 0.0) {
      V.col(2) *= -1.0;
      sigma(2) *= -1.0;
    }
  }
  Mat3 rotation() const { return U * V.transpose(); }
  /// Directional derivative of R = U V^T along dF (polar decomposition).
  Mat3 rotation_derivative(const Mat3& dF) const {
    Mat3 M = U.transpose() * dF * V;
    Mat3 W = Mat3::Zero();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        if (i == j) continue;
        double s = sigma(i) + sigma(j);
        if (std::abs(s) < 1e-12) s = s < 0 ? -1e-12 : 1e-12;
        W(i, j) = (M(i, j) - M(j, i)) / s;
      }
    return U * W * V.transpose();
  }
};

/// The rotation of the polar decomposition F = R S by Higham's Newton iteration
/// X <- (X + X^-T) / 2, which converges quadratically for det F > 0 and is
/// several times cheaper than an SVD; false for nearly flat or inverted F.
/// Each singular value s of X goes to (s + 1/s) / 2: a step that moves it by
/// d < 1e-8 leaves it within 2 d^2 of 1. So a step below 1e-8 (X is then a
/// rotation, of unit size, to 1e-8) leaves X one to round-off, and the loop
/// stops there (waiting for a step of 1e-14 took one more inverse).
bool newton_polar_rotation(const Mat3& F, Mat3& R) {
  const double scale = F.squaredNorm() / 3.0;  // mean squared singular value
  if (!(F.determinant() > 1e-3 * scale * std::sqrt(scale))) return false;
  R = F;
  for (int k = 0; k < 30; ++k) {
    Mat3 next = 0.5 * (R + R.inverse().transpose());
    double change = (next - R).squaredNorm();
    R = next;
    if (change < 1e-16) return true;
  }
  return false;
}

/// dR/dF of F = R S in closed form (9x9 on column-major vec, as tangent_from_directions).
/// dR = R [w]x, and the skew part of R^T dF = [w]x S + dS gives (tr S I - S) w =
/// axial(R^T dF - dF^T R) = B^T vec(dF), where column k of B is vec(R [e_k]x).
/// So dR/dF = B (tr S I - S)^-1 B^T: symmetric, rank 3. S must be positive definite.
Mat9 polar_rotation_derivative(const Mat3& R, const Mat3& S) {
  Eigen::Matrix<double, 9, 3> B;
  // vec(R [e_k]x): its column j is R (e_k x e_j).
  B.col(0) << Vec3::Zero(), R.col(2), -R.col(1);
  B.col(1) << -R.col(2), Vec3::Zero(), R.col(0);
  B.col(2) << R.col(1), -R.col(0), Vec3::Zero();
  const Mat3 G = S.trace() * Mat3::Identity() - S;
  const Eigen::Matrix<double, 9, 3> BH = B.lazyProduct(G.inverse());
  return BH.lazyProduct(B.transpose());  // coefficient-wise: a 9x9 result is too small for a blocked product
}

}  // namespace

Mat3 polar_rotation(const Mat3& F) {
  Mat3 R;
  if (newton_polar_rotation(F, R)) return R;
  return RotationSvd(F).rotation();
}

Lame Lame::from_young_poisson(double young, double poisson) {
  Lame l;
  l.mu = young / (2.0 * (1.0 + poisson));
  l.lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  return l;
}

MaterialLaw::MaterialLaw(MaterialModel model, double young, double poisson, bool definite_tangent)
    : model_(model),
      lame_(Lame::from_young_poisson(young, poisson)),
      definite_tangent_(definite_tangent),
      linear_(model == MaterialModel::linear) {
  KERF_CHECK(model != MaterialModel::user, "a registered material law is made from the scene's Material");
}

MaterialLaw::MaterialLaw(const Material& m, bool definite_tangent)
    : model_(m.model),
      lame_(Lame::from_young_poisson(m.young, m.poisson)),
      definite_tangent_(definite_tangent),
      linear_(m.model == MaterialModel::linear) {
  if (model_ != MaterialModel::user) return;
  const UserMaterialEntry* entry = find_user_material(m.user_model);
  KERF_CHECK(entry, "material.model: '", m.user_model, "' is not registered in this program");
  user_ = entry->make(m);
  KERF_CHECK(user_, "material.model: the factory of '", m.user_model, "' made no law");
  linear_ = user_->is_linear();
}

double MaterialLaw::energy(const Mat3& F) const {
  const double lambda = lame_.lambda, mu = lame_.mu;
  switch (model_) {
    case MaterialModel::linear: {
      Mat3 e = sym(F) - Mat3::Identity();
      return mu * e.squaredNorm() + 0.5 * lambda * e.trace() * e.trace();
    }
    case MaterialModel::corotational: {
      Mat3 R = polar_rotation(F);
      double t = (R.transpose() * F).trace() - 3.0;
      return mu * (F - R).squaredNorm() + 0.5 * lambda * t * t;
    }
    case MaterialModel::stvk: {
      Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
      return mu * E.squaredNorm() + 0.5 * lambda * E.trace() * E.trace();
    }
    case MaterialModel::neohookean: {
      double J = F.determinant();
      if (!(J > 0.0)) return std::numeric_limits<double>::infinity();
      double logJ = std::log(J);
      return 0.5 * mu * (F.squaredNorm() - 3.0) - mu * logJ + 0.5 * lambda * logJ * logJ;
    }
    case MaterialModel::neohookean_uncoupled: {
      const double J = F.determinant();
      if (!(J > 0.0)) return std::numeric_limits<double>::infinity();
      return 0.5 * mu * (std::pow(J, -2.0 / 3.0) * F.squaredNorm() - 3.0) + 0.5 * bulk_coefficient() * (J - 1.0) * (J - 1.0);
    }
    case MaterialModel::user:
      return user_->energy(F);
  }
  return 0.0;
}

Mat3 MaterialLaw::stress(const Mat3& F) const {
  const double lambda = lame_.lambda, mu = lame_.mu;
  const Mat3 I = Mat3::Identity();
  switch (model_) {
    case MaterialModel::linear: {
      Mat3 e = sym(F) - I;
      return lambda * e.trace() * I + 2.0 * mu * e;
    }
    case MaterialModel::corotational: {
      Mat3 R = polar_rotation(F);
      return 2.0 * mu * (F - R) + lambda * ((R.transpose() * F).trace() - 3.0) * R;
    }
    case MaterialModel::stvk: {
      Mat3 E = 0.5 * (F.transpose() * F - I);
      return F * (lambda * E.trace() * I + 2.0 * mu * E);
    }
    case MaterialModel::neohookean: {
      double J = F.determinant();
      if (!(J > 0.0)) return Mat3::Constant(std::numeric_limits<double>::quiet_NaN());
      Mat3 FinvT = F.inverse().transpose();
      return mu * (F - FinvT) + lambda * std::log(J) * FinvT;
    }
    case MaterialModel::neohookean_uncoupled: {
      const double J = F.determinant();
      if (!(J > 0.0)) return Mat3::Constant(std::numeric_limits<double>::quiet_NaN());
      const Mat3 FinvT = F.inverse().transpose();
      return mu * std::pow(J, -2.0 / 3.0) * (F - F.squaredNorm() / 3.0 * FinvT) + bulk_coefficient() * (J - 1.0) * J * FinvT;
    }
    case MaterialModel::user:
      return user_->stress(F);
  }
  return Mat3::Zero();
}

void MaterialLaw::exact_tangent(const Mat3& F, Mat3& P, Mat9& dPdF) const {
  const double lambda = lame_.lambda, mu = lame_.mu;
  const Mat3 I = Mat3::Identity();
  switch (model_) {
    case MaterialModel::linear: {
      P = stress(F);
      dPdF = tangent_from_directions([&](const Mat3& dF) {
        Mat3 de = sym(dF);
        return Mat3(lambda * de.trace() * I + 2.0 * mu * de);
      });
      return;
    }
    case MaterialModel::corotational: {
      // dP = 2 mu (dF - dR) + lambda tr(R^T dF) R + lambda t dR, with t = tr S - 3.
      Mat3 R;
      if (newton_polar_rotation(F, R)) {
        const Mat3 S = sym(R.transpose() * F);
        const double t = S.trace() - 3.0;
        P = 2.0 * mu * (F - R) + lambda * t * R;
        const Eigen::Map<const Eigen::Matrix<double, 9, 1>> r(R.data());
        dPdF = (lambda * t - 2.0 * mu) * polar_rotation_derivative(R, S) + lambda * r * r.transpose();
        dPdF.diagonal().array() += 2.0 * mu;
        return;
      }
      // Nearly flat or inverted: the SVD's rotation, which has a negative singular value there.
      RotationSvd svd(F);
      R = svd.rotation();
      const double t = svd.sigma.sum() - 3.0;
      P = 2.0 * mu * (F - R) + lambda * t * R;
      dPdF = tangent_from_directions([&](const Mat3& dF) {
        Mat3 dR = svd.rotation_derivative(dF);
        return Mat3(2.0 * mu * (dF - dR) + lambda * (R.transpose() * dF).trace() * R + lambda * t * dR);
      });
      return;
    }
    case MaterialModel::stvk: {
      Mat3 E = 0.5 * (F.transpose() * F - I);
      Mat3 S = lambda * E.trace() * I + 2.0 * mu * E;
      P = F * S;
      dPdF = tangent_from_directions([&](const Mat3& dF) {
        Mat3 dE = sym(F.transpose() * dF);
        return Mat3(dF * S + F * (lambda * dE.trace() * I + 2.0 * mu * dE));
      });
      return;
    }
    case MaterialModel::neohookean: {
      double J = F.determinant();
      if (!(J > 0.0)) {
        P = Mat3::Constant(std::numeric_limits<double>::quiet_NaN());
        dPdF = Mat9::Constant(std::numeric_limits<double>::quiet_NaN());
        return;
      }
      Mat3 Finv = F.inverse();
      Mat3 FinvT = Finv.transpose();
      double logJ = std::log(J);
      P = mu * (F - FinvT) + lambda * logJ * FinvT;
      dPdF = tangent_from_directions([&](const Mat3& dF) {
        return Mat3(mu * dF + (mu - lambda * logJ) * FinvT * dF.transpose() * FinvT +
                    lambda * (Finv * dF).trace() * FinvT);
      });
      return;
    }
    case MaterialModel::neohookean_uncoupled: {
      P = stress(F);
      if (!P.allFinite()) {
        dPdF = Mat9::Constant(std::numeric_limits<double>::quiet_NaN());
        return;
      }
      const double J = F.determinant(), a = std::pow(J, -2.0 / 3.0), I1 = F.squaredNorm(), K = bulk_coefficient();
      const Mat3 Finv = F.inverse(), FinvT = Finv.transpose();
      dPdF = tangent_from_directions([&](const Mat3& dF) {
        const double trace = (Finv * dF).trace();  // dJ / J
        const Mat3 dFinvT = -FinvT * dF.transpose() * FinvT;
        const Mat3 isochoric = -2.0 / 3.0 * a * trace * (F - I1 / 3.0 * FinvT) +
                               a * (dF - 2.0 / 3.0 * (F.array() * dF.array()).sum() * FinvT - I1 / 3.0 * dFinvT);
        return Mat3(mu * isochoric + K * ((2.0 * J - 1.0) * J * trace * FinvT + J * (J - 1.0) * dFinvT));
      });
      return;
    }
    case MaterialModel::user:
      user_->stress_and_tangent(F, P, dPdF);
      return;
  }
}

void MaterialLaw::stress_and_tangent(const Mat3& F, Mat3& P, Mat9& dPdF) const {
  exact_tangent(F, P, dPdF);
  make_definite(dPdF);
}

void MaterialLaw::make_definite(Mat9& dPdF) const {
  if (!definite_tangent_ || is_linear()) return;
  dPdF = 0.5 * (dPdF + dPdF.transpose()).eval();
  // Cheap test first: a Cholesky of the slightly shifted matrix succeeds when
  // nothing needs projecting (rigid rotations leave exact zeros at rest).
  const double shift = 1e-10 * std::abs(dPdF.trace()) + 1e-300;
  if (Eigen::LLT<Mat9>(dPdF + shift * Mat9::Identity()).info() == Eigen::Success) return;
  const Eigen::SelfAdjointEigenSolver<Mat9> eigen(dPdF);
  dPdF = eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() * eigen.eigenvectors().transpose();
}

MaterialLaw::BulkMeasure MaterialLaw::bulk_measure(const Mat3& F) const {
  switch (model_) {
    case MaterialModel::linear:
      return {F.trace() - 3.0, Mat3::Identity()};
    case MaterialModel::corotational: {
      const RotationSvd svd(F);
      return {svd.sigma.sum() - 3.0, svd.rotation()};  // tr(R^T F) = tr S; its gradient is R
    }
    case MaterialModel::stvk:
      return {0.5 * (F.squaredNorm() - 3.0), F};
    case MaterialModel::neohookean: {
      const double J = F.determinant();
      if (!(J > 0.0)) return {std::numeric_limits<double>::quiet_NaN(), Mat3::Zero()};
      return {std::log(J), F.inverse().transpose()};
    }
    case MaterialModel::neohookean_uncoupled: {
      const double J = F.determinant();
      return {J - 1.0, J * F.inverse().transpose()};
    }
    case MaterialModel::user:
      break;
  }
  KERF_CHECK(false, "internal: a registered material law has no bulk measure");
  return {};
}

Mat9 MaterialLaw::bulk_measure_hessian(const Mat3& F) const {
  switch (model_) {
    case MaterialModel::linear:
      return Mat9::Zero();
    case MaterialModel::corotational: {
      Mat3 R;
      if (newton_polar_rotation(F, R)) return polar_rotation_derivative(R, sym(R.transpose() * F));
      const RotationSvd svd(F);
      return tangent_from_directions([&](const Mat3& dF) { return svd.rotation_derivative(dF); });
    }
    case MaterialModel::stvk:
      return Mat9::Identity();
    case MaterialModel::neohookean: {
      const Mat3 FinvT = F.inverse().transpose();
      return tangent_from_directions([&](const Mat3& dF) { return Mat3(-FinvT * dF.transpose() * FinvT); });
    }
    case MaterialModel::neohookean_uncoupled: {
      const double J = F.determinant();
      const Mat3 Finv = F.inverse(), FinvT = Finv.transpose();
      return tangent_from_directions([&](const Mat3& dF) {
        return Mat3(J * (Finv * dF).trace() * FinvT - J * FinvT * dF.transpose() * FinvT);
      });
    }
    case MaterialModel::user:
      break;
  }
  KERF_CHECK(false, "internal: a registered material law has no bulk measure");
  return {};
}

double MaterialLaw::energy_without_bulk(const Mat3& F) const {
  const double m = bulk_measure(F).value;
  return energy(F) - 0.5 * bulk_coefficient() * m * m;
}

Mat3 MaterialLaw::averaged_bulk_stress(const Mat3& F, const BulkMeasure& own, double averaged) const {
  return stress(F) + bulk_coefficient() * (averaged - own.value) * own.gradient;
}

void MaterialLaw::averaged_bulk_stress_and_tangent(const Mat3& F, const BulkMeasure& own, double averaged, Mat3& P,
                                                   Mat9& dPdF) const {
  exact_tangent(F, P, dPdF);
  const double k = bulk_coefficient();
  const Eigen::Map<const Eigen::Matrix<double, 9, 1>> g(own.gradient.data());
  P += k * (averaged - own.value) * own.gradient;
  dPdF -= k * g * g.transpose();
  if (model_ != MaterialModel::linear) dPdF += k * (averaged - own.value) * bulk_measure_hessian(F);
  make_definite(dPdF);
}

Mat3 MaterialLaw::cauchy_stress(const Mat3& F) const {
  return stress(F) * F.transpose() / F.determinant();
}

double von_mises(const Mat3& s) {
  double a = s(0, 0) - s(1, 1), b = s(1, 1) - s(2, 2), c = s(2, 2) - s(0, 0);
  double shear = s(0, 1) * s(0, 1) + s(1, 2) * s(1, 2) + s(2, 0) * s(2, 0);
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * shear);
}

}  // namespace kerf

