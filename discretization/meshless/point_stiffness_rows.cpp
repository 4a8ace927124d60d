// PointIntegration::add_stiffness_rows: the points' material stiffness written
// row by row straight into a CSR matrix (see point_integration.h).
#include <algorithm>
#include <cstdint>
#include <cstring>

#include "core/check.h"
#include "core/parallel_failure.h"
#include "discretization/meshless/point_integration.h"

namespace kerf {
namespace {

/// The matrix's arrays and the points' data a row reads.
struct RowInputs {
  const ShapeTable& table;
  const NeighborLists& users;
  std::span<const Index> user_point;  // per entry of users.index
  std::span<const double> weights;
  std::span<const Mat9> tangents;  // one per point, or one for every point
  const CsrView& K;
};

/// A node pair a point couples that the matrix's pattern leaves out (none: point -1).
struct MissingPair {
  Index point = -1, a = -1, b = -1;
};

// The 32-byte vectors below never cross a call (every helper is always
// inlined), so the baseline build's ABI note on returning them does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"
typedef double v4d __attribute__((vector_size(32)));

/// A thread's scratch: offset_of by node (-1 but while a row is written), and
/// the sums of a row's upper blocks (DIM vectors a block).
struct RowScratch {
  std::vector<Index> offset_of;
  std::vector<double> storage;  // sums(), 32-byte aligned in it (a std::vector<v4d> need not be)
  v4d* sums() {
    const std::size_t misaligned = reinterpret_cast<std::uintptr_t>(storage.data()) % 32;
    return reinterpret_cast<v4d*>(storage.data() + (misaligned ? (32 - misaligned) / sizeof(double) : 0));
  }
};

/// Slot s's gradient in lanes 0 to DIM - 1; the lanes after them hold the
/// next slot's entries (ignored), except at the table's last slot.
template <int DIM>
__attribute__((always_inline)) inline v4d gradient_lanes(const double* gradient, Index s, Index slots) {
  v4d g = {0.0, 0.0, 0.0, 0.0};
  if (DIM == 3 && s + 1 < slots)  // one load (a copy of varying length is a loop of small ones)
    std::memcpy(&g, gradient + DIM * s, sizeof g);
  else
    std::memcpy(&g, gradient + DIM * s, DIM * sizeof(double));
  return g;
}

/// Node a's upper node blocks, K_ab for b >= a: sum over the points p holding
/// a of w_p g_a^T dPdF_p g_b; p's neighbours are ascending, so b runs over the
/// slots from a's on. The sums gather in `sums` (per thread, in L1: DIM rows
/// of 4 lanes a block, lanes past DIM ignored) and reach K once a block. With
/// one tangent for every point (a linear law) they are the moments M_ab =
/// sum_p w_p g_a g_b^T, a third of the work a pair, and K_ab = dP/dF : M_ab;
/// otherwise K_ab's rows. `offset_of[b]`: b's first column in a's rows (-1
/// where the pattern has none), set here and cleared before returning. False,
/// with `missing`, at a pair the pattern leaves out (nothing written then).
template <int DIM, bool Shared>
__attribute__((always_inline)) inline bool add_upper_row(const RowInputs& in, Index a, std::vector<Index>& offset_of,
                                                         v4d* sums, MissingPair& missing) {
  const Index r = DIM * a, begin = in.K.outer[r], length = in.K.outer[r + 1] - begin;
  if (in.users.start[a] == in.users.start[a + 1]) return true;
  const Index* columns = in.K.inner + begin;
  for (Index t = 0; t < length; t += DIM) offset_of[columns[t] / DIM] = t;
  const Index diagonal = offset_of[a];  // a's own columns: the first block of the upper half
  if (diagonal < 0) {                    // a pattern without them (build_pattern's always has them)
    missing = {in.user_point[in.users.start[a]], a, a};
    for (Index t = 0; t < length; t += DIM) offset_of[columns[t] / DIM] = -1;
    return false;
  }
  std::fill(sums, sums + (length - diagonal), v4d{0.0, 0.0, 0.0, 0.0});
  const Index* start = in.table.neighbours.start.data();
  const Index* index = in.table.neighbours.index.data();
  const double* gradient = in.table.gradient.data();
  const Index slots = static_cast<Index>(in.table.neighbours.index.size());
  bool whole = true;
  for (Index k = in.users.start[a]; k < in.users.start[a + 1] && whole; ++k) {
    const Index s = in.users.index[k], p = in.user_point[k];
    if (k + 8 < in.users.start[a + 1]) {  // a later point's entries: scattered, their misses the loop's cost
      const Index later = in.users.index[k + 8];
      __builtin_prefetch(gradient + DIM * later);
      __builtin_prefetch(gradient + DIM * later + 8);
      __builtin_prefetch(index + later);
    }
    const double* ga = gradient + DIM * s;
    // Shared: row j of M_ab += (w g_a(j)) g_b. Else S[i][l][c] = w sum_j g_a(j) dP(i,j)/dF(c,l), and row i
    // of K_ab += sum_l S[i][l] g_b(l).
    v4d S[DIM][DIM];
    double wa[DIM];
    if constexpr (Shared) {
      for (int j = 0; j < DIM; ++j) wa[j] = in.weights[p] * ga[j];
    } else {
      const Mat9& D = in.tangents[p];
      for (int i = 0; i < DIM; ++i)
        for (int l = 0; l < DIM; ++l) {
          v4d column = {0.0, 0.0, 0.0, 0.0};
          for (int c = 0; c < DIM; ++c) {
            double t = 0.0;
            for (int j = 0; j < DIM; ++j) t += ga[j] * D(i + 3 * j, c + 3 * l);
            column[c] = in.weights[p] * t;
          }
          S[i][l] = column;
        }
    }
    for (Index slot = s; slot < start[p + 1]; ++slot) {
      const Index b = index[slot], at = offset_of[b];
      if (at < 0) {
        missing = {p, a, b}, whole = false;
        break;
      }
      const v4d gb = gradient_lanes<DIM>(gradient, slot, slots);
      v4d* block = sums + (at - diagonal);  // DIM vectors a block: at - diagonal is DIM a block
      for (int i = 0; i < DIM; ++i) {
        if constexpr (Shared) {
          block[i] += wa[i] * gb;
        } else {
          v4d k_row = S[i][0] * gb[0];
          for (int l = 1; l < DIM; ++l) k_row += S[i][l] * gb[l];
          block[i] += k_row;
        }
      }
    }
  }
  if (whole) {
    double* row[DIM];
    for (int i = 0; i < DIM; ++i) row[i] = in.K.values + in.K.outer[r + i];
    for (Index at = diagonal; at < length; at += DIM) {
      const v4d* block = sums + (at - diagonal);
      for (int i = 0; i < DIM; ++i)
        for (int c = 0; c < DIM; ++c) {
          double t = 0.0;
          if constexpr (Shared) {  // K_ab(i, c) = sum_jl dP(i,j)/dF(c,l) M(j, l)
            for (int j = 0; j < DIM; ++j)
              for (int l = 0; l < DIM; ++l) t += in.tangents[0](i + 3 * j, c + 3 * l) * block[j][l];
          } else {
            t = block[i][c];
          }
          row[i][at + c] += t;
        }
    }
  }
  for (Index t = 0; t < length; t += DIM) offset_of[columns[t] / DIM] = -1;
  return whole;
}

/// This thread's share of the nodes' upper rows, compiled for the baseline and
/// for AVX2 + FMA (every thread of the region calls it). `missing`: the first
/// pair the pattern leaves out, if any; an empty `offset_of` (its allocation
/// failed) does nothing.
template <int DIM, bool Shared>
__attribute__((always_inline)) inline void add_upper_rows(const RowInputs& in, Index nodes, RowScratch& scratch,
                                                          MissingPair& missing) {
#pragma omp for schedule(dynamic, 16)
  for (Index a = 0; a < nodes; ++a)
    if (missing.point < 0 && !scratch.offset_of.empty())
      add_upper_row<DIM, Shared>(in, a, scratch.offset_of, scratch.sums(), missing);
}

__attribute__((always_inline)) inline void add_upper_rows_any(const RowInputs& in, Index nodes, RowScratch& scratch,
                                                              MissingPair& missing) {
  const bool shared = in.tangents.size() == 1;
  if (in.table.dimension == 2)
    shared ? add_upper_rows<2, true>(in, nodes, scratch, missing) : add_upper_rows<2, false>(in, nodes, scratch, missing);
  else if (shared)
    add_upper_rows<3, true>(in, nodes, scratch, missing);
  else
    add_upper_rows<3, false>(in, nodes, scratch, missing);
}

void upper_rows_baseline(const RowInputs& in, Index nodes, RowScratch& scratch, MissingPair& missing) {
  add_upper_rows_any(in, nodes, scratch, missing);
}

__attribute__((target("avx2,fma"))) void upper_rows_avx2(const RowInputs& in, Index nodes, RowScratch& scratch,
                                                        MissingPair& missing) {
  add_upper_rows_any(in, nodes, scratch, missing);
}

using UpperRows = void (*)(const RowInputs&, Index, RowScratch&, MissingPair&);

UpperRows best_upper_rows() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") ? upper_rows_avx2 : upper_rows_baseline;
}

/// Node a's lower node blocks K_ac (c < a) copied from the transposes of K_ca,
/// where row c holds a (on an MPI rank a row it does not touch holds its diagonal
/// alone, and K_ac is then zero and left as it is).
void copy_lower_row(const CsrView& K, int dim, Index a) {
  const Index r = dim * a, begin = K.outer[r];
  for (Index t = 0; begin + t < K.outer[r + 1] && K.inner[begin + t] < r; t += dim) {
    const Index c = K.inner[begin + t] / dim;
    const Index* first = K.inner + K.outer[dim * c];
    const Index* last = K.inner + K.outer[dim * c + 1];
    const Index* at = std::lower_bound(first, last, r);
    if (at == last || *at != r) continue;
    const Index offset = static_cast<Index>(at - first);
    for (int i = 0; i < dim; ++i)
      for (int k = 0; k < dim; ++k) K.values[K.outer[r + i] + t + k] = K.values[K.outer[dim * c + k] + offset + i];
  }
}

/// The longest row of the nodes' rows; refuses a pattern whose node rows
/// differ in length (not one of whole nodes).
Index longest_node_row(const CsrView& K, int dim, Index nodes) {
  Index longest = 0;
  for (Index a = 0; a < nodes; ++a) {
    const Index length = K.outer[dim * a + 1] - K.outer[dim * a];
    longest = std::max(longest, length);
    for (int i = 1; i < dim; ++i)
      KERF_CHECK(K.outer[dim * a + i + 1] - K.outer[dim * a + i] == length, "internal: the rows of node ", a,
                 " differ in length: the pattern is not one of whole nodes");
  }
  return longest;
}

}  // namespace

void PointIntegration::add_stiffness_rows(std::span<const Mat9> tangents, const CsrView& K) const {
  const int dim = shapes_.dimension;
  const Index nodes = users_.size();
  KERF_CHECK(tangents.size() == 1 || static_cast<Index>(tangents.size()) == point_count(), "internal: ",
             tangents.size(), " tangents for ", point_count(), " points");
  KERF_CHECK(K.rows >= dim * nodes, "internal: a matrix of ", K.rows, " rows for ", nodes, " nodes");
  const Index longest_row = longest_node_row(K, dim, nodes);
  const RowInputs in{shapes_, users_, user_point_, weights_, tangents, K};
  static const UpperRows upper_rows = best_upper_rows();
  ParallelFailure failure;  // the scratch allocates
  MissingPair first_missing;
#pragma omp parallel
  {
    RowScratch scratch;
    MissingPair missing;
    failure.run([&] {
      scratch.storage.resize(4 * longest_row + 4);
      scratch.offset_of.assign((K.rows + dim - 1) / dim, -1);
    });
    upper_rows(in, nodes, scratch, missing);
#pragma omp critical(kerf_missing_pair)
    if (missing.point >= 0 && first_missing.point < 0) first_missing = missing;
#pragma omp barrier
    // Every upper block is final here: the lower ones are copied from them.
    if (!failure.failed() && first_missing.point < 0) {
#pragma omp for schedule(dynamic, 64) nowait
      for (Index a = 0; a < nodes; ++a) copy_lower_row(K, dim, a);
    }
  }
  failure.rethrow_if_failed();
  KERF_CHECK(first_missing.point < 0, "internal: point ", first_missing.point, " couples nodes ", first_missing.a,
             " and ", first_missing.b, ", which the matrix's pattern leaves out");
}

}  // namespace kerf
