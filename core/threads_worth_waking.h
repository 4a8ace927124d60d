#pragma once
// When a parallel loop is worth its threads. kerf's threads sleep when they
// wait (passive, core/thread_policy.h), so every parallel region and every
// barrier in it wakes them: about 50 us each on the 2-core VM, more than a
// few hundred cells' or nodes' forces take. A 173-node tet4 block's explicit
// step took 1.38 ms on two threads against 0.099 ms on one (its cells
// coloured into many phases, a barrier each). Below this many items a thread
// and a phase, a loop runs on one thread.
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
