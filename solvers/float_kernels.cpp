#include "solvers/float_kernels.h"

namespace kerf {

const FloatKernels& baseline_float_kernels_build();  // float_kernels_impl.cpp, built once per set
const FloatKernels& avx2_float_kernels_build();

const FloatKernels& baseline_float_kernels() { return baseline_float_kernels_build(); }

const FloatKernels* avx2_float_kernels() {
  static const bool supported = [] {
    __builtin_cpu_init();
    // The processor's, and the OS's (it saves the 256-bit registers).
    return __builtin_cpu_supports("avx2") != 0 && __builtin_cpu_supports("fma") != 0;
  }();
  return supported ? &avx2_float_kernels_build() : nullptr;
}

const FloatKernels& float_kernels() {
  static const FloatKernels& chosen = avx2_float_kernels() ? *avx2_float_kernels() : baseline_float_kernels();
  return chosen;
}

}  // namespace kerf
