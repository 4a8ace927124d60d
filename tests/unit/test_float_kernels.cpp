// The float factor's dense kernels: each build (baseline, and AVX2 with FMA
// where the processor has them) against a double-precision reference, to
// float's round-off, so the two builds agree to that (not bit for bit: FMA
// rounds once where the baseline rounds twice); sizes on both sides of the vectors'
// widths and of Eigen's blocks.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "solvers/float_kernels.h"

namespace kerf {
namespace {

struct Results {
  std::vector<float> solved, solved_transposed, product, subtracted;
};

/// Each kernel once on a rows x cols block (leading dimension rows + 3) whose
/// top cols x cols is lower triangular with a dominant diagonal.
Results run(const FloatKernels& k, const Eigen::MatrixXf& A, const Eigen::VectorXf& x, const Eigen::VectorXf& v) {
  const std::ptrdiff_t ld = A.rows(), rows = A.rows() - 3, cols = A.cols();
  Results r;
  r.solved.assign(x.data(), x.data() + cols);
  k.lower_solve(A.data(), ld, cols, r.solved.data());
  r.solved_transposed.assign(x.data(), x.data() + cols);
  k.lower_transpose_solve(A.data(), ld, cols, r.solved_transposed.data());
  r.product.assign(rows, 7.0f);  // overwritten
  k.times(A.data(), ld, rows, cols, x.data(), r.product.data());
  r.subtracted.assign(x.data(), x.data() + cols);
  k.subtract_transpose_times(A.data(), ld, rows, cols, v.data(), r.subtracted.data());
  return r;
}

double relative_error(const std::vector<float>& got, const Eigen::VectorXd& want) {
  const Eigen::VectorXd g = Eigen::Map<const Eigen::VectorXf>(got.data(), got.size()).cast<double>();
  return (g - want).norm() / want.norm();
}

TEST(FloatKernels, EachBuildSolvesAndMultipliesToFloatRoundOff) {
  const FloatKernels* avx2 = avx2_float_kernels();
  if (!avx2) std::printf("this processor lacks AVX2: the baseline build alone is checked\n");
  EXPECT_EQ(&float_kernels(), avx2 ? avx2 : &baseline_float_kernels());
  for (int cols : {1, 3, 4, 5, 15, 16, 17, 33, 70})
    for (int rows : {cols, cols + 1, cols + 16, 3 * cols + 37}) {
      std::srand(rows * 100 + cols);
      Eigen::MatrixXf A = Eigen::MatrixXf::Random(rows + 3, cols);
      for (int j = 0; j < cols; ++j) {
        A.col(j).head(j).setZero();
        A(j, j) = 4.0f + static_cast<float>(j % 3);
      }
      const Eigen::VectorXf x = Eigen::VectorXf::Random(cols), v = Eigen::VectorXf::Random(rows);
      const Eigen::MatrixXd L = A.topRows(cols).cast<double>(), B = A.topRows(rows).cast<double>();
      const Eigen::VectorXd xd = x.cast<double>(), vd = v.cast<double>();
      const double tolerance = 1e-6 * (1.0 + 0.01 * rows);
      for (const FloatKernels* k : {&baseline_float_kernels(), avx2}) {
        if (!k) continue;
        const Results r = run(*k, A, x, v);
        const std::string name = std::string(k->instruction_set) + ", " + std::to_string(rows) + " x " +
                                 std::to_string(cols);
        EXPECT_LT(relative_error(r.solved, L.triangularView<Eigen::Lower>().solve(xd)), tolerance) << name;
        EXPECT_LT(relative_error(r.solved_transposed, L.transpose().triangularView<Eigen::Upper>().solve(xd)),
                  tolerance) << name;
        EXPECT_LT(relative_error(r.product, B * xd), tolerance) << name;
        EXPECT_LT(relative_error(r.subtracted, xd - B.transpose() * vd), tolerance) << name;
      }
    }
}

}  // namespace
}  // namespace kerf
