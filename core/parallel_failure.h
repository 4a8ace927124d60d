#pragma once
// The first exception thrown by any thread of an OpenMP region, carried out
// of it. An exception leaving a region ends the process in std::terminate
// (no summary, no message naming the key), and one leaving a thread between
// two of a region's barriers hangs the others; so each unit of a region's
// work runs through run(), which keeps the first exception, skips the work
// that is left, and lets every thread reach the region's barriers. The
// calling thread rethrows after the region.
#include <atomic>
#include <exception>
#include <mutex>

#include "core/types.h"

namespace kerf {

class ParallelFailure {
 public:
  template <class Work>
  void run(Work&& work) noexcept {
    if (failed_.load(std::memory_order_relaxed)) return;
    try {
      work();
    } catch (...) {
      keep(std::current_exception());
    }
  }
  bool failed() const { return failed_.load(std::memory_order_relaxed); }
  /// On the thread that opened the region, after it.
  void rethrow_if_failed() const {
    if (first_) std::rethrow_exception(first_);
  }

 private:
  void keep(std::exception_ptr e) noexcept {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!first_) first_ = std::move(e);
    failed_.store(true, std::memory_order_relaxed);
  }
  std::atomic<bool> failed_{false};
  std::mutex mutex_;
  std::exception_ptr first_;
};

/// work(i, scratch) for every i < count on the region's threads, each with
/// its own Scratch (default-made, so nothing it holds is shared), in dynamic
/// chunks of 16; the first exception is rethrown after the region.
template <class Scratch, class Work>
void for_each_with_scratch(Index count, Work&& work) {
  ParallelFailure failure;
#pragma omp parallel
  {
    Scratch scratch;
#pragma omp for schedule(dynamic, 16)
    for (Index i = 0; i < count; ++i) failure.run([&] { work(i, scratch); });
  }
  failure.rethrow_if_failed();
}

}  // namespace kerf
