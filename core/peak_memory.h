#pragma once
// This process's largest resident set so far: what summary.json reports at
// the run's milestones, per rank, so memory per rank can be followed phase by
// phase (Linux's getrusage; ru_maxrss is in kilobytes there).
#include <sys/resource.h>

namespace kerf {

inline double peak_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

}  // namespace kerf
