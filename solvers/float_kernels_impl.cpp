// The kernels of float_kernels.h on Eigen's, compiled once per instruction set
// (solvers/CMakeLists.txt defines KERF_KERNEL_SET and the flags). The AVX2
// build renames Eigen's namespace, so that its template instantiations are
// its own: the linker cannot hand an AVX2 copy of one to the baseline's code
// (a weak symbol defined twice keeps one copy), which the test
// unit.Avx2KernelsDefineNoSharedSymbol checks on the object file.
#ifdef KERF_OWN_EIGEN_NAMESPACE
#define Eigen KERF_OWN_EIGEN_NAMESPACE
#endif
#include <Eigen/Core>

#include "solvers/float_kernels.h"

#define KERF_KERNEL_FUNCTION(set) KERF_KERNEL_FUNCTION_(set)
#define KERF_KERNEL_FUNCTION_(set) set##_float_kernels_build
#define KERF_STRING(set) KERF_STRING_(set)
#define KERF_STRING_(set) #set

namespace kerf {
namespace {

using Size = std::ptrdiff_t;
using Block = Eigen::Map<const Eigen::MatrixXf, 0, Eigen::OuterStride<>>;
using Column = Eigen::Map<Eigen::VectorXf>;
using ConstColumn = Eigen::Map<const Eigen::VectorXf>;

void lower_solve(const float* L, Size ld, Size n, float* x) {
  Column v(x, n);
  const Block block(L, n, n, Eigen::OuterStride<>(ld));
  block.triangularView<Eigen::Lower>().solveInPlace(v);
}

void lower_transpose_solve(const float* L, Size ld, Size n, float* x) {
  Column v(x, n);
  const Block block(L, n, n, Eigen::OuterStride<>(ld));
  block.triangularView<Eigen::Lower>().transpose().solveInPlace(v);
}

void times(const float* A, Size ld, Size rows, Size cols, const float* x, float* y) {
  Column(y, rows).noalias() = Block(A, rows, cols, Eigen::OuterStride<>(ld)) * ConstColumn(x, cols);
}

void subtract_transpose_times(const float* A, Size ld, Size rows, Size cols, const float* x, float* y) {
  Column(y, cols).noalias() -= Block(A, rows, cols, Eigen::OuterStride<>(ld)).transpose() * ConstColumn(x, rows);
}

constexpr FloatKernels kernels{KERF_STRING(KERF_KERNEL_SET), lower_solve, lower_transpose_solve, times,
                               subtract_transpose_times};

}  // namespace

/// This build's table (float_kernels.cpp picks one).
const FloatKernels& KERF_KERNEL_FUNCTION(KERF_KERNEL_SET)() { return kernels; }

}  // namespace kerf
