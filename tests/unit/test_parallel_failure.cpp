// Exceptions thrown inside OpenMP regions reach the caller (an exception that
// leaves a region ends the process in std::terminate): the helper alone, then
// the bodies' real assembly loops with a sink that fails part way.
#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <stdexcept>

#include "core/check.h"
#include "core/parallel_failure.h"
#include "discretization/body_factory.h"
#include "support/test_support.h"

namespace kerf {
namespace {

TEST(ParallelFailure, TheFirstExceptionReachesTheCallerWithItsTypeAndTheRestIsSkipped) {
  const int n = 100000;
  std::atomic<int> done{0};
  ParallelFailure failure;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    failure.run([&] {
      if (i == 137) throw std::out_of_range("item 137");
      ++done;
    });
  EXPECT_TRUE(failure.failed());
  try {
    failure.rethrow_if_failed();
    FAIL() << "no exception came out of the region";
  } catch (const std::out_of_range& e) {
    EXPECT_STREQ(e.what(), "item 137");
  }
  // The thread that threw stopped at its item 137 of its share.
  EXPECT_LE(done.load(), n - n / omp_get_max_threads() + 137);
}

TEST(ParallelFailure, NothingThrownNothingRethrown) {
  ParallelFailure failure;
#pragma omp parallel for
  for (int i = 0; i < 1000; ++i) failure.run([] {});
  EXPECT_FALSE(failure.failed());
  EXPECT_NO_THROW(failure.rethrow_if_failed());
}

/// A 2 x 2 x 2 cm block at 5 mm, by method.
std::unique_ptr<DiscreteBody> block(const std::string& method) {
  Scene scene = testing::scene_from_text(
      "domain: {box: {min: [0,0,0], max: [0.02,0.02,0.02]}}\n"
      "material: {young: 1.0e4, poisson: 0.3}\n"
      "boundary: [{select: {plane: {axis: x, at: 0.0}}, fix: [x, y, z]}]\n"
      "discretization: {method: " + method + ", fem: {size: 0.005}, meshless: {spacing: 0.005}}\n"
      "solve: {analysis: static}\n");
  RunReport report;
  return make_body(scene, report);
}

// Each body's tangent assembly runs in parallel and hands every block to the
// sink: a sink that refuses its tenth block must stop the assembly with its
// own error, on the calling thread.
TEST(ParallelFailure, ASinkFailingInsideEveryBodysAssemblyReachesTheCaller) {
  for (const std::string method : {"fem", "efg", "nodal"}) {
    const auto body = block(method);
    std::atomic<int> blocks{0};
    const BlockSink refusing = [&](std::span<const Index>, std::span<const double>) {
      if (++blocks == 10) throw Error("the tenth block is refused");
    };
    Vector f;
    try {
      body->tangent(Vector::Zero(body->dof_count()), refusing, &f);
      ADD_FAILURE() << method << ": the sink's error did not reach the caller";
    } catch (const Error& e) {
      EXPECT_STREQ(e.what(), "the tenth block is refused") << method;
    }
    EXPECT_GE(blocks.load(), 10) << method;
  }
}

}  // namespace
}  // namespace kerf
