// Phase timing: a timer started inside another pauses it, so every second is
// counted in one phase and the phases of a run add up to its wall time.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "core/timer.h"

namespace kerf {
namespace {

TEST(PhaseTimes, ANestedTimerPausesTheOuterOne) {
  PhaseTimes times;
  const double start = now_seconds();
  {
    ScopedTimer output(times, Phase::output);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    {
      ScopedTimer assembly(times, Phase::assembly);
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const double wall = now_seconds() - start;
  EXPECT_GE(times.seconds(Phase::assembly), 0.2);
  EXPECT_GE(times.seconds(Phase::output), 0.04);
  // Not the 0.24 s the outer timer lasted: the inner timer's time is not counted twice.
  EXPECT_LT(times.seconds(Phase::output), 0.15);
  EXPECT_NEAR(times.seconds(Phase::output) + times.seconds(Phase::assembly), wall, 1e-3);
}

}  // namespace
}  // namespace kerf
