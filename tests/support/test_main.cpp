// main() of every GoogleTest executable: the same OpenMP thread cap as `kerf`.
#include <gtest/gtest.h>

#include "core/denormals.h"
#include "core/thread_policy.h"

int main(int argc, char** argv) {
  kerf::apply_thread_policy(argv);
  kerf::flush_denormals_to_zero();
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
