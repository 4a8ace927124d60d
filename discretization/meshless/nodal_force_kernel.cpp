#include "discretization/meshless/nodal_force_kernel.h"

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "core/threads_worth_waking.h"

namespace kerf {
namespace {

// The 32-byte vectors below never cross a call (every helper is always
// inlined), so the baseline build's ABI note on returning them does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"
typedef double v4d __attribute__((vector_size(32)));

__attribute__((always_inline)) inline v4d load4(const double* p) {  // 4 doubles, any alignment
  v4d v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// Slot s's gradient in lanes 0-2; lane 3 is the next slot's first entry
/// (ignored), except at the table's last slot, which has no next.
__attribute__((always_inline)) inline v4d gradient4(const NodalForceTables& t, Index s) {
  if (s + 1 < t.slots) return load4(t.gradient + 3 * s);
  v4d v = {0.0, 0.0, 0.0, 0.0};
  std::memcpy(&v, t.gradient + 3 * s, 3 * sizeof(double));
  return v;
}

/// One node's gather, stress and scatter into `mine` (4 per node); with
/// `Corrected`, neighbour K is tested with grad psi_K plus its VCI offset.
template <bool Stabilized, bool Corrected>
__attribute__((always_inline)) inline void node_pass(const NodalForceTables& t, const MaterialLaw& law,
                                                     const double* u4, double* mine, Index I) {
  const Index s0 = t.start[I], s1 = t.start[I + 1];
  const v4d xI = *reinterpret_cast<const v4d*>(t.position4 + 4 * I);
  // h_i = row i of grad u; d_i = row i of sum_K u_K (k_IK X_IK)^T.
  v4d h0 = {}, h1 = {}, h2 = {}, d0 = {}, d1 = {}, d2 = {};
  for (Index s = s0; s < s1; ++s) {
    const double* uK = u4 + 4 * t.index[s];
    const v4d g = gradient4(t, s);
    h0 += uK[0] * g, h1 += uK[1] * g, h2 += uK[2] * g;
    if constexpr (Stabilized) {
      const v4d c = t.stiffness[s] * (*reinterpret_cast<const v4d*>(t.position4 + 4 * t.index[s]) - xI);
      d0 += uK[0] * c, d1 += uK[1] * c, d2 += uK[2] * c;
    }
  }
  const v4d h[3] = {h0, h1, h2}, d[3] = {d0, d1, d2};
  Mat3 F;
  for (int i = 0; i < 3; ++i)
    for (int l = 0; l < 3; ++l) F(i, l) = (i == l ? 1.0 : 0.0) + h[i][l];
  const Mat3 P = law.stress(F);
  const double* uI = u4 + 4 * I;
  // Columns of q = V P - (d - u_I s_I^T - h M_I) and of h, as vectors over i.
  // VCI tests only V P with xi (p_col): the pair terms are Galerkin.
  v4d q_col[3], h_col[3], p_col[3];
  for (int l = 0; l < 3; ++l) {
    v4d q = {}, hc = {}, p = {};
    for (int i = 0; i < 3; ++i) {
      double value = t.volume[I] * P(i, l);
      p[i] = value;
      if constexpr (Stabilized) {
        double hM = 0.0;
        for (int m = 0; m < 3; ++m) hM += h[i][m] * t.lever_moment[9 * I + 3 * m + l];
        value -= d[i][l] - uI[i] * t.lever_sum[3 * I + l] - hM;
      }
      q[i] = value;
      hc[i] = h[i][l];
    }
    q_col[l] = q, h_col[l] = hc, p_col[l] = p;
  }
  const v4d a_I = *reinterpret_cast<const v4d*>(uI) - (h_col[0] * xI[0] + h_col[1] * xI[1] + h_col[2] * xI[2]);
  v4d push = {};
  for (Index s = s0; s < s1; ++s) {
    const Index K = t.index[s];
    const double* g = t.gradient + 3 * s;
    v4d force = q_col[0] * g[0] + q_col[1] * g[1] + q_col[2] * g[2];
    if constexpr (Corrected) {
      const double* o = t.test_offset + 3 * s;
      force += p_col[0] * o[0] + p_col[1] * o[1] + p_col[2] * o[2];
    }
    if constexpr (Stabilized) {
      const double* xK = t.position4 + 4 * K;
      const v4d w = *reinterpret_cast<const v4d*>(u4 + 4 * K) - (h_col[0] * xK[0] + h_col[1] * xK[1] + h_col[2] * xK[2]);
      const v4d e = t.stiffness[s] * (w - a_I);
      force += e;
      push += e;
    }
    v4d* fK = reinterpret_cast<v4d*>(mine + 4 * K);
    *fK += force;
  }
  *reinterpret_cast<v4d*>(mine + 4 * I) -= push;
}

template <bool Stabilized, bool Corrected>
__attribute__((always_inline)) inline void nodes_pass(const NodalForceTables& t, const MaterialLaw& law,
                                                      const double* u4, double* mine) {
#pragma omp for schedule(static)
  for (Index I = t.pass_begin; I < t.pass_end; ++I) node_pass<Stabilized, Corrected>(t, law, u4, mine, I);
}

__attribute__((always_inline)) inline void nodes_pass_any(const NodalForceTables& t, const MaterialLaw& law,
                                                          const double* u4, double* mine) {
  if (t.test_offset)
    t.stiffness ? nodes_pass<true, true>(t, law, u4, mine) : nodes_pass<false, true>(t, law, u4, mine);
  else
    t.stiffness ? nodes_pass<true, false>(t, law, u4, mine) : nodes_pass<false, false>(t, law, u4, mine);
}

/// The pass over this thread's nodes, compiled for the baseline and for AVX2 + FMA.
void nodes_pass_baseline(const NodalForceTables& t, const MaterialLaw& law, const double* u4, double* mine) {
  nodes_pass_any(t, law, u4, mine);
}

__attribute__((target("avx2,fma"))) void nodes_pass_avx2(const NodalForceTables& t, const MaterialLaw& law,
                                                         const double* u4, double* mine) {
  nodes_pass_any(t, law, u4, mine);
}

using NodesPass = void (*)(const NodalForceTables&, const MaterialLaw&, const double*, double*);

NodesPass best_nodes_pass() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") ? nodes_pass_avx2 : nodes_pass_baseline;
}

}  // namespace

const double* aligned_32(const std::vector<double>& buffer) {
  const std::size_t misaligned = reinterpret_cast<std::uintptr_t>(buffer.data()) % 32;
  return buffer.data() + (misaligned ? (32 - misaligned) / sizeof(double) : 0);
}

std::vector<double> padded_positions(std::span<const Vec3> positions) {
  std::vector<double> buffer(4 * positions.size() + 4, 0.0);
  double* p = const_cast<double*>(aligned_32(buffer));
  for (std::size_t n = 0; n < positions.size(); ++n)
    for (int i = 0; i < 3; ++i) p[4 * n + i] = positions[n][i];
  return buffer;
}

void nodal_force_3d(const NodalForceTables& t, const MaterialLaw& law, const Vector& u, Vector& f,
                    NodalForceScratch& scratch, VectorUnit unit) {
  static const NodesPass best = best_nodes_pass();
  const NodesPass pass = unit == VectorUnit::best ? best : nodes_pass_baseline;
  const Index N = t.nodes;
  const bool every = t.touched.empty();
  const Index count = every ? N : static_cast<Index>(t.touched.size());
  f.resize(3 * N);
  if (!every) f.setZero();  // the nodes no term reaches: the rows of the other ranks' parts
  scratch.u4.resize(4 * static_cast<std::size_t>(N) + 4);
  // 32-byte aligned starts inside the buffers (vector<double> guarantees 16).
  double* u4 = const_cast<double*>(aligned_32(scratch.u4));
  // Sized here, not inside the region: an allocation failure must not be thrown in it.
  const std::size_t stride = 4 * static_cast<std::size_t>(N);
  scratch.forces4.resize(omp_get_max_threads() * stride + 4);
#pragma omp parallel if (worth_threads(count))
  {
    const int thread = omp_get_thread_num(), threads = omp_get_num_threads();
    double* all = const_cast<double*>(aligned_32(scratch.forces4));
    double* mine = all + thread * stride;
    if (every)
      std::fill(mine, mine + stride, 0.0);
    else
      for (Index I : t.touched) std::fill(mine + 4 * I, mine + 4 * I + 4, 0.0);
#pragma omp for schedule(static)
    for (Index k = 0; k < count; ++k) {
      const Index I = every ? k : t.touched[k];
      for (int i = 0; i < 3; ++i) u4[4 * I + i] = u[3 * I + i];
      u4[4 * I + 3] = 0.0;
    }
    pass(t, law, u4, mine);  // ends with the loop's barrier: every thread's forces complete
#pragma omp for schedule(static)
    for (Index k = 0; k < count; ++k) {
      const Index I = every ? k : t.touched[k];
      for (int i = 0; i < 3; ++i) {
        double sum = 0.0;
        for (int r = 0; r < threads; ++r) sum += all[r * stride + 4 * I + i];
        f[3 * I + i] = sum;
      }
    }
  }
}

}  // namespace kerf
