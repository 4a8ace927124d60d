#pragma once
// When a parallel loop is worth its threads. kerf's threads sleep when they
// wait (passive, core/thread_policy.h), so every parallel region and every
// barrier in it wakes them: an empty region takes 37 us on the 2-core VM
// against 1.1 us with active waiting (BM_ThreadWakeEmptyParallelRegion). A
// 173-node tet4 block's explicit step took 1.38 ms on two threads against
// 0.099 ms on one: its cells coloured into many phases, a barrier each.
// An item is about 0.2 us of one thread's work: a tet4 cell in an explicit step
// (0.20-0.22 us, the timing study's block and cube on one thread), a 3D
// nodal node's forces (0.30 us), 512 values gathered (0.21 us,
// BM_ThreadWakeGather256Values), 384 entries of a float factor's solve (0.57
// ns an entry). A loop runs on one thread below items_worth_a_thread items a
// thread and a phase: about 100 us each, three wakes' worth.
#include <omp.h>

#include "core/types.h"

namespace kerf {

inline constexpr Index items_worth_a_thread = 512;

/// Whether `items` of work, split over the threads kerf runs, are worth waking them for.
inline bool worth_threads(Index items) {
  const int threads = omp_get_max_threads();
  return threads > 1 && items >= items_worth_a_thread * threads;
}

}  // namespace kerf
