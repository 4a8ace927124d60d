#pragma once
// Wall-clock phase timing: a ScopedTimer adds its lifetime to a named phase.
#include <chrono>
#include <map>
#include <string>

namespace kerf {

/// Accumulated seconds per phase (setup, assembly, factorize, solve, cut_update,
/// output). Timers of different phases never nest, so the phases add up.
class PhaseTimes {
 public:
  void add(const std::string& phase, double seconds) { seconds_[phase] += seconds; }
  const std::map<std::string, double>& all() const { return seconds_; }

 private:
  std::map<std::string, double> seconds_;
};

inline double now_seconds() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

class ScopedTimer {
 public:
  ScopedTimer(PhaseTimes& times, std::string phase)
      : times_(times), phase_(std::move(phase)), start_(now_seconds()) {}
  ~ScopedTimer() { times_.add(phase_, now_seconds() - start_); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  PhaseTimes& times_;
  std::string phase_;
  double start_;
};

}  // namespace kerf
