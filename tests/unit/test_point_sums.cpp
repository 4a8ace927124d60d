// add_over_points sums every point's additions into per-node arrays in a
// fixed number of parts: every point counted once (point counts below and
// past the parts, not a multiple of them), the same bits on one thread or
// two, and the serial sum to round-off.
#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>

#include "discretization/meshless/point_sums.h"

namespace kerf {
namespace {

TEST(PointSums, EveryPointOnceTheSameBitsOnAnyThreadCount) {
  for (Index points : {0, 1, 3, 4, 7, 1001}) {
    auto add = [](Index p, double* sums) {
      sums[p % 5] += 1.0 / (1.0 + p);  // round-off depends on the order
      sums[5] += 1.0;                  // counts the points
    };
    std::vector<double> serial(6, 0.5);
    for (Index p = 0; p < points; ++p) add(p, serial.data());
    std::vector<std::vector<double>> by_threads;
    for (int threads : {1, 2}) {
      const int before = omp_get_max_threads();
      omp_set_num_threads(threads);
      std::vector<double> sums(6, 0.5);
      add_over_points(points, sums, add);
      omp_set_num_threads(before);
      by_threads.push_back(sums);
    }
    EXPECT_EQ(by_threads[0], by_threads[1]) << points << " points";
    EXPECT_EQ(by_threads[0][5], 0.5 + points);
    for (int j = 0; j < 5; ++j) EXPECT_NEAR(by_threads[0][j], serial[j], 1e-14) << points << " points, entry " << j;
  }
}

TEST(PointSums, AThrowingTermReachesTheCaller) {
  std::vector<double> sums(1, 0.0);
  EXPECT_THROW(add_over_points(100, sums, [](Index p, double*) {
                 if (p == 77) throw std::runtime_error("point 77");
               }),
               std::runtime_error);
}

}  // namespace
}  // namespace kerf
