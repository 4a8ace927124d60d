#pragma once
// Ctrl-C (SIGINT) and SIGTERM (a batch system's or a user's kill) ask a run
// to stop: the handler only records the signal, and the work stops at the
// next place that asks (a step, a Newton iteration, a phase of the set-up, a
// study's point), so the summary and every file written stay readable. A
// second signal while the first is being honoured ends the process at once.
#include <atomic>
#include <csignal>

#include "core/check.h"

namespace kerf {

/// A run stopped by a signal: summary.json says "interrupted", not "error".
class Interrupted : public Error {
 public:
  Interrupted(int signal, const std::string& where)
      : Error(std::string("interrupted (") + (signal == SIGTERM ? "SIGTERM" : "SIGINT, Ctrl-C") + ") " + where +
              "; the results written so far are complete and readable"),
        signal_(signal) {}
  int signal() const { return signal_; }

 private:
  int signal_;
};

namespace detail {
inline volatile std::sig_atomic_t pending_signal = 0;
inline std::atomic<int> interrupt_scopes{0};
inline void record_signal(int signal) {
  if (pending_signal != 0) {  // asked twice: stop now
    std::signal(signal, SIG_DFL);
    std::raise(signal);
  }
  pending_signal = signal;
}
}  // namespace detail

/// While one lives, SIGINT and SIGTERM are recorded instead of ending the
/// process; the outermost (a study's around its runs) installs and restores.
class InterruptScope {
 public:
  InterruptScope() {
    if (detail::interrupt_scopes++ > 0) return;
    detail::pending_signal = 0;
    previous_int_ = std::signal(SIGINT, detail::record_signal);
    previous_term_ = std::signal(SIGTERM, detail::record_signal);
  }
  ~InterruptScope() {
    if (--detail::interrupt_scopes > 0) return;
    std::signal(SIGINT, previous_int_);
    std::signal(SIGTERM, previous_term_);
  }
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  void (*previous_int_)(int) = SIG_DFL;
  void (*previous_term_)(int) = SIG_DFL;
};

/// Throws Interrupted, saying where (the parts are joined), once a signal came.
template <class... Parts>
void stop_if_interrupted(const Parts&... where) {
  if (const int signal = detail::pending_signal) throw Interrupted(signal, detail::concat(where...));
}

}  // namespace kerf
