#pragma once
// A phase that says nothing for minutes (gmsh meshing a large body: it has
// no progress report short of hundreds of lines per mesh) shows it is alive:
// every period a line on stderr with the seconds elapsed, until it ends.
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

namespace kerf {

class ProgressHeartbeat {
 public:
  /// Prints "kerf: <what>, N s so far" every `period` while alive.
  ProgressHeartbeat(std::string what, std::chrono::seconds period)
      : what_(std::move(what)), period_(period), thread_([this] { beat(); }) {}
  ~ProgressHeartbeat() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
    }
    wake_.notify_one();
    thread_.join();
  }
  ProgressHeartbeat(const ProgressHeartbeat&) = delete;
  ProgressHeartbeat& operator=(const ProgressHeartbeat&) = delete;

 private:
  void beat() {
    const auto started = std::chrono::steady_clock::now();
    std::unique_lock<std::mutex> lock(mutex_);
    while (!wake_.wait_for(lock, period_, [this] { return done_; })) {
      const auto seconds =
          std::chrono::duration_cast<std::chrono::seconds>(std::chrono::steady_clock::now() - started).count();
      std::fprintf(stderr, "kerf: %s, %lld s so far\n", what_.c_str(), static_cast<long long>(seconds));
    }
  }

  std::string what_;
  std::chrono::seconds period_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::thread thread_;  // last: starts once the rest is built
};

}  // namespace kerf
