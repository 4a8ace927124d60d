#include "discretization/meshless/mls_shape.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace kerf {
namespace {

/// p(xi) for xi = (y - x) / h: [1, xi_1..xi_dim, (quadratic) xi_i xi_j for i <= j].
template <int M>
Eigen::Matrix<double, M, 1> basis_at(int dim, MlsBasis basis, const Vec3& xi) {
  Eigen::Matrix<double, M, 1> p;
  int k = 0;
  p[k++] = 1.0;
  for (int i = 0; i < dim; ++i) p[k++] = xi[i];
  if (basis == MlsBasis::quadratic)
    for (int i = 0; i < dim; ++i)
      for (int j = i; j < dim; ++j) p[k++] = xi[i] * xi[j];
  return p;
}

}  // namespace

int mls_basis_size(int dim, MlsBasis basis) {
  return 1 + dim + (basis == MlsBasis::quadratic ? dim * (dim + 1) / 2 : 0);
}

WeightValue quartic_weight(const Vec3& x, const Vec3& node, double radius, bool with_hessian) {
  const WeightWithGradient first = quartic_weight_with_gradient(x, node, radius);
  WeightValue w{first.value, first.gradient, Mat3::Zero()};
  const Vec3 s = x - node;
  const double distance = s.norm(), r = distance / radius;
  if (!with_hessian || r >= 1.0) return w;
  const double a = 1.0 - r, d2 = radius * radius;
  w.hessian = -12.0 / d2 * a * a * Mat3::Identity();
  if (distance > 0.0) w.hessian += 24.0 / d2 * a * s * s.transpose() / (distance * radius);
  return w;
}

bool mls_shape_functions(int dim, MlsBasis basis, const Vec3& x, std::span<const Vec3> nodes,
                         std::span<const double> radii, bool hessians, MlsShape& out) {
  std::vector<WeightValue> w(nodes.size());
  for (std::size_t I = 0; I < nodes.size(); ++I) w[I] = quartic_weight(x, nodes[I], radii[I]);
  const double h = radii.empty() ? 1.0 : *std::max_element(radii.begin(), radii.end());
  return mls_shape_functions(dim, basis, x, nodes, w, h, hessians, out);
}

namespace {

/// The MLS shape functions for an m-term basis p (m = M when known at compile
/// time, so every moment matrix and solve is fixed-size): p_of(I) is p at
/// node I, p0, dp[k] and d2p[k][l] are p and its derivatives at x. Nothing is
/// allocated but `out`.
template <int M, class BasisAtNode>
bool mls_with_basis(int dim, int m, std::size_t n, BasisAtNode p_of, const Eigen::Matrix<double, M, 1>& p0,
                    const Eigen::Matrix<double, M, 1> (&dp)[3], const Eigen::Matrix<double, M, 1> (&d2p)[3][3],
                    std::span<const WeightValue> w, bool hessians, MlsShape& out) {
  using Column = Eigen::Matrix<double, M, 1>;
  using Square = Eigen::Matrix<double, M, M>;
  Square A = Square::Zero(m, m);
  Square dA[3], d2A[3][3];
  for (int k = 0; k < dim; ++k) {
    dA[k] = Square::Zero(m, m);
    for (int l = 0; l < dim; ++l) d2A[k][l] = Square::Zero(m, m);
  }
  for (std::size_t I = 0; I < n; ++I) {
    const Column p = p_of(I);
    const Square ppT = p * p.transpose();
    A += w[I].value * ppT;
    for (int k = 0; k < dim; ++k) {
      dA[k] += w[I].gradient[k] * ppT;
      if (hessians)
        for (int l = 0; l < dim; ++l) d2A[k][l] += w[I].hessian(k, l) * ppT;
    }
  }
  Eigen::SelfAdjointEigenSolver<Square> eigen(A);
  const auto& lambda = eigen.eigenvalues();
  out.condition = lambda[m - 1] / std::max(lambda[0], 0.0);
  if (!(lambda[0] > 1e-12 * lambda[m - 1])) return false;
  auto solve = [&](const Column& b) -> Column {
    return eigen.eigenvectors() * (lambda.cwiseInverse().asDiagonal() * (eigen.eigenvectors().transpose() * b));
  };
  // gamma = A^-1 p(x) and its derivatives (Belytschko et al.).
  const Column gamma = solve(p0);
  Column dgamma[3], d2gamma[3][3];
  for (int k = 0; k < dim; ++k) dgamma[k] = solve(dp[k] - dA[k] * gamma);
  if (hessians)
    for (int k = 0; k < dim; ++k)
      for (int l = 0; l < dim; ++l)
        d2gamma[k][l] = solve(d2p[k][l] - dA[k] * dgamma[l] - dA[l] * dgamma[k] - d2A[k][l] * gamma);
  for (std::size_t I = 0; I < n; ++I) {
    const Column p = p_of(I);
    const double gp = gamma.dot(p);
    out.value[I] = gp * w[I].value;
    double dgp[3] = {0, 0, 0};
    for (int k = 0; k < dim; ++k) {
      dgp[k] = dgamma[k].dot(p);
      out.gradient[I][k] = dgp[k] * w[I].value + gp * w[I].gradient[k];
    }
    if (!hessians) continue;
    for (int k = 0; k < dim; ++k)
      for (int l = 0; l < dim; ++l)
        out.hessian[I](k, l) = d2gamma[k][l].dot(p) * w[I].value + dgp[k] * w[I].gradient[l] +
                               dgp[l] * w[I].gradient[k] + gp * w[I].hessian(k, l);
  }
  return true;
}

/// Clears `out` for n nodes: zero values and derivatives, infinite condition.
void reset_shape(std::size_t n, bool hessians, MlsShape& out) {
  out.value.assign(n, 0.0);
  out.gradient.assign(n, Vec3::Zero());
  out.hessian.assign(hessians ? n : 0, Mat3::Zero());
  out.condition = std::numeric_limits<double>::infinity();
  out.spanned_directions = -1;
}

/// The full basis (linear or quadratic, M terms), centred at x and scaled by
/// h, the largest support, so that A stays O(1).
template <int M>
bool mls_fixed(int dim, MlsBasis basis, const Vec3& x, std::span<const Vec3> nodes, std::span<const WeightValue> w,
               double h, bool hessians, MlsShape& out) {
  using Column = Eigen::Matrix<double, M, 1>;
  const std::size_t n = nodes.size();
  reset_shape(n, hessians, out);
  if (n == 0) return false;
  auto p_of = [&](std::size_t I) { return basis_at<M>(dim, basis, (nodes[I] - x) / h); };
  // Derivatives of p at the evaluation point (xi = 0): dp/dx_k = e_{1+k} / h;
  // d2p/dx_k dx_l is 1/h^2 (2 on the diagonal) on the quadratic term xi_k xi_l.
  const Column p0 = basis_at<M>(dim, basis, Vec3::Zero());
  Column dp[3], d2p[3][3];
  for (int k = 0; k < 3; ++k) {
    dp[k] = Column::Zero();
    if (k < dim) dp[k][1 + k] = 1.0 / h;
    for (int l = 0; l < 3; ++l) d2p[k][l] = Column::Zero();
  }
  if (basis == MlsBasis::quadratic) {
    int term = 1 + dim;
    for (int i = 0; i < dim; ++i)
      for (int j = i; j < dim; ++j, ++term) {
        double value = (i == j ? 2.0 : 1.0) / (h * h);
        d2p[i][j][term] = value;
        d2p[j][i][term] = value;
      }
  }
  return mls_with_basis<M>(dim, M, n, p_of, p0, dp, d2p, w, hessians, out);
}

}  // namespace

NodeSpread node_spread(int dim, const Vec3& x, std::span<const Vec3> nodes, std::span<const WeightValue> w,
                       double h) {
  NodeSpread spread;
  double total = 0.0;
  Vec3 mean = Vec3::Zero();
  for (std::size_t I = 0; I < nodes.size(); ++I) {
    total += w[I].value;
    mean += w[I].value * (nodes[I] - x) / h;
  }
  if (!(total > 0.0)) return spread;
  mean /= total;
  Mat3 covariance = Mat3::Zero();
  for (std::size_t I = 0; I < nodes.size(); ++I) {
    const Vec3 d = (nodes[I] - x) / h - mean;
    covariance += w[I].value / total * d * d.transpose();
  }
  if (dim == 2) covariance(2, 2) = -1.0;  // 2D: z is never a direction (its eigenvalue sorts first)
  Eigen::SelfAdjointEigenSolver<Mat3> eigen;
  eigen.computeDirect(covariance);  // closed form: no allocation, cheap enough for every point near a cut
  const double largest = eigen.eigenvalues()[2];
  spread.weighted = true;
  for (int k = 2; k >= 3 - dim; --k)
    if (largest > 1e-12 && eigen.eigenvalues()[k] >= NodeSpread::thinnest * largest)
      spread.axes.col(spread.directions++) = eigen.eigenvectors().col(k);
  return spread;
}

bool mls_spanned_linear(int dim, const Vec3& x, std::span<const Vec3> nodes, std::span<const WeightValue> w,
                        const NodeSpread& spread, double h, bool hessians, MlsShape& out) {
  using Column = Eigen::VectorXd;
  const std::size_t n = nodes.size();
  reset_shape(n, hessians, out);
  if (!spread.weighted) return false;
  const int r = spread.directions, m = 1 + r;
  const Eigen::MatrixXd T = spread.axes.topLeftCorner(dim, r);
  auto p_of = [&](std::size_t I) {
    Column p(m);
    p[0] = 1.0;
    p.tail(r) = T.transpose() * ((nodes[I] - x) / h).head(dim);
    return p;
  };
  Column p0 = Column::Zero(m), dp[3], d2p[3][3];
  p0[0] = 1.0;
  for (int k = 0; k < 3; ++k) {
    dp[k] = Column::Zero(m);
    if (k < dim) dp[k].tail(r) = T.row(k).transpose() / h;
    for (int l = 0; l < 3; ++l) d2p[k][l] = Column::Zero(m);
  }
  if (!mls_with_basis<Eigen::Dynamic>(dim, m, n, p_of, p0, dp, d2p, w, hessians, out)) return false;
  out.spanned_directions = r;
  return true;
}

bool mls_shape_functions(int dim, MlsBasis basis, const Vec3& x, std::span<const Vec3> nodes,
                         std::span<const WeightValue> w, double h, bool hessians, MlsShape& out) {
  switch (mls_basis_size(dim, basis)) {
    case 3: return mls_fixed<3>(dim, basis, x, nodes, w, h, hessians, out);    // 2D linear
    case 4: return mls_fixed<4>(dim, basis, x, nodes, w, h, hessians, out);    // 3D linear
    case 6: return mls_fixed<6>(dim, basis, x, nodes, w, h, hessians, out);    // 2D quadratic
    default: return mls_fixed<10>(dim, basis, x, nodes, w, h, hessians, out);  // 3D quadratic
  }
}

}  // namespace kerf
