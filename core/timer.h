#pragma once
// Wall-clock phase timing: a ScopedTimer adds its lifetime to one of the
// phases every run is timed in, the same for every method.
#include <array>
#include <chrono>

namespace kerf {

enum class Phase { setup, assembly, factorize, solve, cut_update, output };
inline constexpr std::array<const char*, 6> phase_names{"setup", "assembly", "factorize", "solve", "cut_update",
                                                        "output"};

class ScopedTimer;

/// Accumulated seconds per phase. A timer started inside another (a reaction
/// probe that assembles the stiffness while the output is timed) pauses the
/// outer one, so each second goes to one phase and the phases add up.
class PhaseTimes {
 public:
  PhaseTimes() = default;
  PhaseTimes(const PhaseTimes& other) : seconds_(other.seconds_) {}  // a copy runs no timer
  PhaseTimes& operator=(const PhaseTimes& other) {
    seconds_ = other.seconds_;
    return *this;
  }
  void add(Phase phase, double seconds) { seconds_[static_cast<std::size_t>(phase)] += seconds; }
  double seconds(Phase phase) const { return seconds_[static_cast<std::size_t>(phase)]; }

 private:
  friend class ScopedTimer;
  std::array<double, phase_names.size()> seconds_{};
  ScopedTimer* running_ = nullptr;  // the innermost timer now running (timers are started on one thread)
};

inline double now_seconds() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

class ScopedTimer {
 public:
  ScopedTimer(PhaseTimes& times, Phase phase)
      : times_(times), phase_(phase), outer_(times.running_), start_(now_seconds()) {
    if (outer_) outer_->pause(start_);
    times_.running_ = this;
  }
  ~ScopedTimer() {
    const double now = now_seconds();
    times_.add(phase_, now - start_);
    times_.running_ = outer_;
    if (outer_) outer_->start_ = now;
  }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  void pause(double now) { times_.add(phase_, now - start_); }
  PhaseTimes& times_;
  Phase phase_;
  ScopedTimer* outer_;
  double start_;
};

}  // namespace kerf
