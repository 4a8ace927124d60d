#pragma once
// CHOLMOD 5 opens OpenMP regions with a fixed 4 threads; on a 2-core machine
// that makes a factorization 2-3 times slower. The only cap libgomp honours is
// OMP_THREAD_LIMIT, read when the library loads: so when it is unset, the
// program sets it to the number of cores and starts itself again, once.
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <thread>

namespace kerf {

inline void limit_openmp_threads_to_cores(char** argv) {
  if (std::getenv("OMP_THREAD_LIMIT")) return;
  unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  ::setenv("OMP_THREAD_LIMIT", std::to_string(cores).c_str(), 1);
  ::execv("/proc/self/exe", argv);
  // If the exec fails, carry on with the unlimited library.
}

}  // namespace kerf
