#include "nodal_floor.h"

#include <omp.h>

#include <algorithm>
#include <cstring>

#include "discretization/meshless/nodal_force_kernel.h"

namespace kerf::bench {
namespace {

#pragma GCC diagnostic ignored "-Wpsabi"  // vectors never cross a call: everything below is inlined
typedef double v4d __attribute__((vector_size(32)));

template <bool Stabilized>
__attribute__((target("avx2,fma"))) void floor_pass(const NodalFloorData& d, const double* u4, double* f4,
                                                    std::vector<double>& scratch) {
  const Index N = static_cast<Index>(d.volume.size()), slots = static_cast<Index>(d.index.size());
  const std::size_t stride = 4 * static_cast<std::size_t>(N);
#pragma omp parallel
  {
    const int thread = omp_get_thread_num(), threads = omp_get_num_threads();
#pragma omp single
    scratch.resize(threads * stride + 4);
    double* all = const_cast<double*>(aligned_32(scratch));
    double* mine = all + thread * stride;
    std::fill(mine, mine + stride, 0.0);
#pragma omp for schedule(static)
    for (Index I = 0; I < N; ++I) {
      const Index s0 = d.start[I], s1 = d.start[I + 1];
      const v4d xI = *reinterpret_cast<const v4d*>(d.position4 + 4 * I);
      v4d h0 = {}, h1 = {}, h2 = {}, e0 = {}, e1 = {}, e2 = {};
      for (Index s = s0; s < s1; ++s) {
        const double* uK = u4 + 4 * d.index[s];
        v4d g = {0.0, 0.0, 0.0, 0.0};  // lane 3: the next slot's first entry, ignored
        if (s + 1 < slots)
          std::memcpy(&g, d.gradient.data() + 3 * s, 4 * sizeof(double));
        else
          std::memcpy(&g, d.gradient.data() + 3 * s, 3 * sizeof(double));
        h0 += uK[0] * g, h1 += uK[1] * g, h2 += uK[2] * g;
        if constexpr (Stabilized) {
          const v4d c = d.stiffness[s] * (*reinterpret_cast<const v4d*>(d.position4 + 4 * d.index[s]) - xI);
          e0 += uK[0] * c, e1 += uK[1] * c, e2 += uK[2] * c;
        }
      }
      const v4d h[3] = {h0, h1, h2}, lever[3] = {e0, e1, e2};
      const double trace = h0[0] + h1[1] + h2[2];
      v4d q_col[3] = {}, h_col[3] = {};
      for (int l = 0; l < 3; ++l)
        for (int i = 0; i < 3; ++i) {
          // Hooke's law, and for the stabilisation the reaction through F_I
          // (its full form needs per-node lever sums; the floor keeps the
          // per-pair work, which is what costs).
          q_col[l][i] = d.volume[I] * (d.mu * (h[i][l] + h[l][i]) + (i == l ? d.lambda * trace : 0.0)) -
                        (Stabilized ? lever[i][l] : 0.0);
          h_col[l][i] = h[i][l];
        }
      const v4d a_I = *reinterpret_cast<const v4d*>(u4 + 4 * I) -
                      (h_col[0] * xI[0] + h_col[1] * xI[1] + h_col[2] * xI[2]);
      v4d push = {};
      for (Index s = s0; s < s1; ++s) {
        const Index K = d.index[s];
        const double* g = d.gradient.data() + 3 * s;
        v4d force = q_col[0] * g[0] + q_col[1] * g[1] + q_col[2] * g[2];
        if constexpr (Stabilized) {
          const double* xK = d.position4 + 4 * K;
          const v4d w = *reinterpret_cast<const v4d*>(u4 + 4 * K) -
                        (h_col[0] * xK[0] + h_col[1] * xK[1] + h_col[2] * xK[2]);
          const v4d e = d.stiffness[s] * (w - a_I);
          force += e;
          push += e;
        }
        *reinterpret_cast<v4d*>(mine + 4 * K) += force;
      }
      *reinterpret_cast<v4d*>(mine + 4 * I) -= push;
    }
#pragma omp for schedule(static)
    for (std::size_t j = 0; j < stride; ++j) {
      double sum = 0.0;
      for (int t = 0; t < threads; ++t) sum += all[t * stride + j];
      f4[j] = sum;
    }
  }
}

}  // namespace

bool nodal_floor_supported() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}

void nodal_floor_force(const NodalFloorData& data, bool stabilized, const double* u4, double* f4,
                       std::vector<double>& scratch) {
  stabilized ? floor_pass<true>(data, u4, f4, scratch) : floor_pass<false>(data, u4, f4, scratch);
}

}  // namespace kerf::bench
