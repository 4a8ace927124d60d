#pragma once
// The dense single-precision kernels of a supernodal triangular solve
// (single_precision_factor.h): Eigen's, built twice, for the baseline
// instruction set and for AVX2 with FMA (256-bit vectors), the latter chosen
// at run time where the processor has them (float_kernels_impl.cpp keeps the
// two builds' templates apart). The two agree to float's round-off, not bit
// for bit. Column-major blocks of leading dimension `ld`.
#include <cstddef>

namespace kerf {

struct FloatKernels {
  const char* instruction_set;
  /// x = L^-1 x, L lower triangular n x n.
  void (*lower_solve)(const float* L, std::ptrdiff_t ld, std::ptrdiff_t n, float* x);
  /// x = L^-T x.
  void (*lower_transpose_solve)(const float* L, std::ptrdiff_t ld, std::ptrdiff_t n, float* x);
  /// y = A x, A rows x cols.
  void (*times)(const float* A, std::ptrdiff_t ld, std::ptrdiff_t rows, std::ptrdiff_t cols, const float* x,
                float* y);
  /// y -= A^T x, A rows x cols.
  void (*subtract_transpose_times)(const float* A, std::ptrdiff_t ld, std::ptrdiff_t rows, std::ptrdiff_t cols,
                                   const float* x, float* y);
};

/// The AVX2 build where the processor runs it (AVX2 and FMA), else the baseline.
const FloatKernels& float_kernels();
/// Each build (for the tests): the second is null where the processor lacks AVX2 or FMA.
const FloatKernels& baseline_float_kernels();
const FloatKernels* avx2_float_kernels();

}  // namespace kerf
