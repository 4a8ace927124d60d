#pragma once
// Wall-clock phase timing: a ScopedTimer adds its lifetime to one of the
// phases every run is timed in, the same for every method.
#include <array>
#include <chrono>

namespace kerf {

enum class Phase { setup, assembly, factorize, solve, cut_update, output };
inline constexpr std::array<const char*, 6> phase_names{"setup", "assembly", "factorize", "solve", "cut_update",
                                                        "output"};

/// Accumulated seconds per phase. Timers of different phases never nest, so
/// the phases add up.
class PhaseTimes {
 public:
  void add(Phase phase, double seconds) { seconds_[static_cast<std::size_t>(phase)] += seconds; }
  double seconds(Phase phase) const { return seconds_[static_cast<std::size_t>(phase)]; }

 private:
  std::array<double, phase_names.size()> seconds_{};
};

inline double now_seconds() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

class ScopedTimer {
 public:
  ScopedTimer(PhaseTimes& times, Phase phase) : times_(times), phase_(phase), start_(now_seconds()) {}
  ~ScopedTimer() { times_.add(phase_, now_seconds() - start_); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  PhaseTimes& times_;
  Phase phase_;
  double start_;
};

}  // namespace kerf
