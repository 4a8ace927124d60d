#include "discretization/meshless/mls_linear.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace kerf {

namespace {

/// One Jacobi rotation zeroing a[p][q], if it is not negligible against the
/// geometric mean of its two diagonal entries (Demmel and Veselic: the small
/// eigenvalues of a positive definite matrix keep their relative accuracy).
template <int M>
__attribute__((always_inline)) inline bool rotate(double (&a)[4][4], int p, int q) {
  constexpr double tolerance = 1e-15;
  const double apq = a[p][q];
  if (!(std::abs(apq) > tolerance * std::sqrt(std::abs(a[p][p] * a[q][q])))) return false;
  // t = tan of the angle = sign(theta) / (|theta| + sqrt(theta^2 + 1)), theta =
  // d / (2 a_pq), written without theta: a division fewer on the chain (and
  // d^2 overflows only for entries past 1e150, far beyond any moment matrix's).
  const double d = a[q][q] - a[p][p], root = std::sqrt(d * d + 4.0 * apq * apq), sum = std::abs(d) + root;
  const double t = 2.0 * std::copysign(1.0, d) * apq / sum;
  const double c = std::sqrt(sum / (2.0 * root)), s = t * c;
  a[p][p] -= t * apq;
  a[q][q] += t * apq;
  a[p][q] = a[q][p] = 0.0;
  for (int r = 0; r < M; ++r) {
    if (r == p || r == q) continue;
    const double arp = a[r][p], arq = a[r][q];
    a[r][p] = a[p][r] = c * arp - s * arq;
    a[r][q] = a[q][r] = s * arp + c * arq;
  }
  return true;
}

/// Jacobi sweeps with the size fixed (the loops unroll). For 4 x 4 the pairs
/// go in the parallel order (0,1)(2,3), (0,2)(1,3), (0,3)(1,2): each step's
/// two rotations touch other rows' diagonals, so the processor overlaps their
/// chains of divisions and square roots, which bound a rotation's time.
template <int M>
void jacobi_eigenvalues(double (&a)[4][4], double (&lambda)[4]) {
  constexpr int pairs = M * (M - 1) / 2;
  constexpr int parallel[6][2] = {{0, 1}, {2, 3}, {0, 2}, {1, 3}, {0, 3}, {1, 2}};
  constexpr int cyclic[3][2] = {{0, 1}, {0, 2}, {1, 2}};  // 2 x 2: its first pair
  for (int sweep = 0; sweep < 40; ++sweep) {
    bool rotated = false;
    for (int k = 0; k < pairs; ++k) {
      if constexpr (M == 4) rotated |= rotate<M>(a, parallel[k][0], parallel[k][1]);
      else rotated |= rotate<M>(a, cyclic[k][0], cyclic[k][1]);
    }
    if (!rotated) break;
  }
  for (int i = 0; i < M; ++i) lambda[i] = a[i][i];
  std::sort(lambda, lambda + M);
}

}  // namespace

void symmetric_eigenvalues(int m, double (&a)[4][4], double (&lambda)[4]) {
  switch (m) {
    case 1: lambda[0] = a[0][0]; return;
    case 2: return jacobi_eigenvalues<2>(a, lambda);
    case 3: return jacobi_eigenvalues<3>(a, lambda);
    default: return jacobi_eigenvalues<4>(a, lambda);
  }
}

namespace {

// The row is compiled for the baseline and for AVX2 + FMA (as the nodal force
// pass is); its two passes over the nodes run on 4-vectors (w and grad w,
// zero-padded in 2D), one register with AVX2. The 32-byte vectors never cross
// a call (everything holding them is inlined into the two builds).
#pragma GCC diagnostic ignored "-Wpsabi"
typedef double Lanes4 __attribute__((vector_size(32)));

/// Where entry (i, j) of a symmetric M x M matrix sits in its upper triangle, row by row.
template <int M>
constexpr int upper_entry(int i, int j) {
  if (i > j) std::swap(i, j);
  return i * M - i * (i - 1) / 2 + (j - i);
}

/// L L^T of a small positive definite matrix, the size fixed so that the
/// loops unroll in the row's two builds (Eigen's LLT was a call a solve,
/// compiled for the baseline); solves in place, one right-hand side a lane.
template <int M>
struct SmallCholesky {
  double l[M][M] = {}, inverse_diagonal[M] = {};
  __attribute__((always_inline)) explicit SmallCholesky(const double (&a)[4][4]) {
    for (int j = 0; j < M; ++j) {
      double d = a[j][j];
      for (int k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
      l[j][j] = std::sqrt(d);
      inverse_diagonal[j] = 1.0 / l[j][j];
      for (int i = j + 1; i < M; ++i) {
        double v = a[i][j];
        for (int k = 0; k < j; ++k) v -= l[i][k] * l[j][k];
        l[i][j] = v * inverse_diagonal[j];
      }
    }
  }
  template <class T>
  __attribute__((always_inline)) void solve(T (&b)[M]) const {
    for (int i = 0; i < M; ++i) {
      for (int k = 0; k < i; ++k) b[i] -= l[i][k] * b[k];
      b[i] *= inverse_diagonal[i];
    }
    for (int i = M - 1; i >= 0; --i) {
      for (int k = i + 1; k < M; ++k) b[i] -= l[k][i] * b[k];
      b[i] *= inverse_diagonal[i];
    }
  }
};

template <int Dim>
__attribute__((always_inline)) inline bool linear_fixed(const Vec3& x, std::span<const Vec3> nodes,
                                                        std::span<const WeightWithGradient> w, double h,
                                                        MlsShape& out) {
  constexpr int M = Dim + 1;
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
  double a[4][4] = {}, moment[4][4] = {}, lambda[4];
  for (int i = 0, e = 0; i < M; ++i)
    for (int j = i; j < M; ++j, ++e) a[i][j] = a[j][i] = moment[i][j] = moment[j][i] = sums[e][0];
  jacobi_eigenvalues<M>(a, lambda);
  out.condition = lambda[M - 1] / std::max(lambda[0], 0.0);
  if (!(lambda[0] > 1e-12 * lambda[M - 1])) return false;
  // gamma = A^-1 p(x) and its derivatives (Belytschko et al.); p(x) = e_0, dp/dx_k = e_{1+k} / h:
  // dgamma_k = A^-1 (e_{1+k} / h - dA_k gamma), the Dim right-hand sides in lanes 1..Dim of one
  // solve, so basis[i] = (gamma_i, dgamma_1i, .., dgamma_Dim,i) for the pass below.
  const SmallCholesky<M> factor(moment);
  double gamma[M] = {1.0};
  factor.solve(gamma);
  Lanes4 basis[M];
  for (int i = 0; i < M; ++i) {
    Lanes4 dA_gamma = {};
    for (int j = 0; j < M; ++j) dA_gamma += sums[upper_entry<M>(i, j)] * gamma[j];
    basis[i] = -dA_gamma;
    if (i > 0) basis[i][i] += inverse_h;
  }
  factor.solve(basis);
  for (int i = 0; i < M; ++i) basis[i][0] = gamma[i];
  // phi_I = (gamma . p) w_I, grad phi_I = (dgamma_k . p) w_I + (gamma . p) grad w_I: the four dot
  // products as one vector sum over the basis.
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
