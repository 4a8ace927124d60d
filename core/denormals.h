#pragma once
// Flush denormal numbers to zero. In explicit dynamics a disturbance reaches
// one more ring of nodes per step with an amplitude that decays geometrically
// ahead of the wave front, so values below 1e-308 appear everywhere in front of
// it, and every operation on them costs ~100x. They carry no physics.
// Call at the start of main(): threads created later (OpenMP's pool) inherit
// the calling thread's floating-point environment.
#include <xmmintrin.h>
#include <pmmintrin.h>

namespace kerf {

inline void flush_denormals_to_zero() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

}  // namespace kerf
