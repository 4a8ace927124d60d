#include "discretization/meshless/mls_linear.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

namespace kerf {

void symmetric_eigenvalues(int m, double (&a)[4][4], double (&lambda)[4]) {
  // A rotation only where the off-diagonal entry is not negligible against
  // the geometric mean of its two diagonal entries (Demmel and Veselic): the
  // small eigenvalues of a positive definite matrix keep their relative accuracy.
  constexpr double tolerance = 1e-15;
  for (int sweep = 0; sweep < 40; ++sweep) {
    bool rotated = false;
    for (int p = 0; p < m; ++p)
      for (int q = p + 1; q < m; ++q) {
        const double apq = a[p][q];
        if (!(std::abs(apq) > tolerance * std::sqrt(std::abs(a[p][p] * a[q][q])))) continue;
        rotated = true;
        const double theta = (a[q][q] - a[p][p]) / (2.0 * apq);
        const double t = std::abs(theta) > 1e150
                             ? 0.5 / theta
                             : std::copysign(1.0, theta) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        a[p][p] -= t * apq;
        a[q][q] += t * apq;
        a[p][q] = a[q][p] = 0.0;
        for (int r = 0; r < m; ++r) {
          if (r == p || r == q) continue;
          const double arp = a[r][p], arq = a[r][q];
          a[r][p] = a[p][r] = c * arp - s * arq;
          a[r][q] = a[q][r] = s * arp + c * arq;
        }
      }
    if (!rotated) break;
  }
  for (int i = 0; i < m; ++i) lambda[i] = a[i][i];
  std::sort(lambda, lambda + m);
}

namespace {

// The row is compiled for the baseline and for AVX2 + FMA (as the nodal force
// pass is); its two passes over the nodes run on 4-vectors (w and grad w,
// zero-padded in 2D), one register with AVX2. The 32-byte vectors never cross
// a call (everything holding them is inlined into the two builds).
#pragma GCC diagnostic ignored "-Wpsabi"
typedef double Lanes4 __attribute__((vector_size(32)));

template <int Dim>
__attribute__((always_inline)) inline bool linear_fixed(const Vec3& x, std::span<const Vec3> nodes,
                                                        std::span<const WeightWithGradient> w, double h,
                                                        MlsShape& out) {
  constexpr int M = Dim + 1;
  using Column = Eigen::Matrix<double, M, 1>;
  using Square = Eigen::Matrix<double, M, M>;
  const std::size_t n = nodes.size();
  out.value.assign(n, 0.0);
  out.gradient.assign(n, Vec3::Zero());
  out.hessian.clear();
  out.spanned_directions = -1;
  out.condition = std::numeric_limits<double>::infinity();
  if (n == 0) return false;
  // p(x_I) = [1, (x_I - x) / h]. sums[e] holds the e-th entry of the upper
  // triangles of A, dA/dx_1 .. dA/dx_Dim: one pass, each node's products
  // p_i p_j times its weight and weight gradient as one short vector.
  constexpr int upper = M * (M + 1) / 2;
  Lanes4 sums[upper] = {};
  const double inverse_h = 1.0 / h;
  for (std::size_t I = 0; I < n; ++I) {
    double p[M];
    p[0] = 1.0;
    for (int i = 0; i < Dim; ++i) p[1 + i] = (nodes[I][i] - x[i]) * inverse_h;
    const Lanes4 c = {w[I].value, w[I].gradient[0], w[I].gradient[1], Dim == 3 ? w[I].gradient[2] : 0.0};
    int e = 0;
    for (int i = 0; i < M; ++i)
      for (int j = i; j < M; ++j, ++e) sums[e] += (p[i] * p[j]) * c;
  }
  double a[4][4] = {}, lambda[4];
  Square moment, derivative[Dim];
  for (int i = 0, e = 0; i < M; ++i)
    for (int j = i; j < M; ++j, ++e) {
      a[i][j] = a[j][i] = moment(i, j) = moment(j, i) = sums[e][0];
      for (int k = 0; k < Dim; ++k) derivative[k](i, j) = derivative[k](j, i) = sums[e][1 + k];
    }
  symmetric_eigenvalues(M, a, lambda);
  out.condition = lambda[M - 1] / std::max(lambda[0], 0.0);
  if (!(lambda[0] > 1e-12 * lambda[M - 1])) return false;
  const Eigen::LLT<Square> factor(moment);
  // gamma = A^-1 p(x) and its derivatives (Belytschko et al.); p(x) = e_0, dp/dx_k = e_{1+k} / h.
  const Column gamma = factor.solve(Column::Unit(0));
  Column dgamma[Dim];
  for (int k = 0; k < Dim; ++k) dgamma[k] = factor.solve(Column::Unit(1 + k) * inverse_h - derivative[k] * gamma);
  // phi_I = (gamma . p) w_I, grad phi_I = (dgamma_k . p) w_I + (gamma . p) grad w_I: the four dot
  // products as one vector sum over the basis, basis[i] = (gamma_i, dgamma_1i, .., dgamma_Dim,i).
  Lanes4 basis[M] = {};
  for (int i = 0; i < M; ++i) {
    basis[i][0] = gamma[i];
    for (int k = 0; k < Dim; ++k) basis[i][1 + k] = dgamma[k][i];
  }
  for (std::size_t I = 0; I < n; ++I) {
    Lanes4 r = basis[0];  // p_0 = 1
    for (int i = 0; i < Dim; ++i) r += ((nodes[I][i] - x[i]) * inverse_h) * basis[1 + i];
    out.value[I] = r[0] * w[I].value;
    for (int k = 0; k < Dim; ++k) out.gradient[I][k] = r[1 + k] * w[I].value + r[0] * w[I].gradient[k];
  }
  return true;
}

using LinearRow = bool (*)(const Vec3&, std::span<const Vec3>, std::span<const WeightWithGradient>, double,
                           MlsShape&);

template <int Dim>
bool linear_baseline(const Vec3& x, std::span<const Vec3> nodes, std::span<const WeightWithGradient> w, double h,
                     MlsShape& out) {
  return linear_fixed<Dim>(x, nodes, w, h, out);
}

template <int Dim>
__attribute__((target("avx2,fma"))) bool linear_avx2(const Vec3& x, std::span<const Vec3> nodes,
                                                     std::span<const WeightWithGradient> w, double h, MlsShape& out) {
  return linear_fixed<Dim>(x, nodes, w, h, out);
}

template <int Dim>
LinearRow best_linear_row() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") ? linear_avx2<Dim> : linear_baseline<Dim>;
}

}  // namespace

bool mls_linear_shape_functions(int dim, const Vec3& x, std::span<const Vec3> nodes,
                                std::span<const WeightWithGradient> w, double scale, MlsShape& out) {
  static const LinearRow row3 = best_linear_row<3>(), row2 = best_linear_row<2>();
  return (dim == 3 ? row3 : row2)(x, nodes, w, scale, out);
}

}  // namespace kerf
