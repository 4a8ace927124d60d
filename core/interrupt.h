#pragma once
// Ctrl-C (SIGINT) and SIGTERM (a batch system's or a user's kill) ask a run
// to stop: the handler only records the signal, and the work stops at the
// next place that asks (a step, a Newton iteration, a phase of the set-up, a
// study's point), so the summary and every file written stay readable. A
// second signal while the first is being honoured ends the process at once;
// so does a watchdog when no such place comes within a few seconds.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

#include "core/check.h"

namespace kerf {

/// A run stopped by a signal: summary.json says "interrupted", not "error".
/// Under mpirun every rank gets the signal (mpirun forwards it): a shared failure.
class Interrupted : public SharedFailure {
 public:
  Interrupted(int signal, const std::string& where)
      : SharedFailure(std::string("interrupted (") + (signal == SIGTERM ? "SIGTERM" : "SIGINT, Ctrl-C") + ") " + where +
                      "; the results written so far are complete and readable"),
        signal_(signal) {}
  int signal() const { return signal_; }

 private:
  int signal_;
};

/// A signal not honoured within this many seconds (a phase that cannot stop
/// midway: gmsh meshing, a factorization) ends the process from a watchdog,
/// after the run's last words (its summary saying "interrupted").
constexpr double interrupt_grace_seconds = 5.0;

namespace detail {
// Written by the handler, read by the run and the watchdog thread: a
// lock-free atomic is both async-signal-safe and free of data races.
inline std::atomic<int> pending_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);
inline std::atomic<int> interrupt_scopes{0};
inline void record_signal(int signal) {
  if (pending_signal != 0) {  // asked twice: stop now
    std::signal(signal, SIG_DFL);
    std::raise(signal);
  }
  pending_signal = signal;
}

struct Watchdog {
  std::mutex mutex;
  std::condition_variable wake;
  bool stop = false;
  std::function<void(int)> last_words;  // under mutex
  std::thread thread;
};
inline Watchdog& watchdog() {
  static Watchdog w;
  return w;
}
inline void watch_for_overdue_signals() {
  Watchdog& w = watchdog();
  std::unique_lock<std::mutex> lock(w.mutex);
  std::optional<std::chrono::steady_clock::time_point> since;
  while (!w.wake.wait_for(lock, std::chrono::milliseconds(100), [&] { return w.stop; })) {
    const int signal = pending_signal;
    if (!signal) continue;
    if (!since) since = std::chrono::steady_clock::now();
    if (std::chrono::steady_clock::now() - *since < std::chrono::duration<double>(interrupt_grace_seconds)) continue;
    std::fprintf(stderr, "kerf: error: interrupted (%s): no point where the run could stop came within %g s "
                 "(gmsh meshing or a factorization runs on); stopped at once, the files written so far readable\n",
                 signal == SIGTERM ? "SIGTERM" : "SIGINT", interrupt_grace_seconds);
    if (w.last_words) w.last_words(signal);
    std::_Exit(1);
  }
}
}  // namespace detail

/// While one lives, SIGINT and SIGTERM are recorded instead of ending the
/// process, and a watchdog ends it if the run does not stop in time; the
/// outermost (a study's around its runs) installs and restores.
class InterruptScope {
 public:
  InterruptScope() {
    if (detail::interrupt_scopes++ > 0) return;
    detail::pending_signal = 0;
    previous_int_ = std::signal(SIGINT, detail::record_signal);
    previous_term_ = std::signal(SIGTERM, detail::record_signal);
    detail::Watchdog& w = detail::watchdog();
    w.stop = false;
    w.thread = std::thread(detail::watch_for_overdue_signals);
  }
  ~InterruptScope() {
    if (--detail::interrupt_scopes > 0) return;
    detail::Watchdog& w = detail::watchdog();
    {
      const std::lock_guard<std::mutex> lock(w.mutex);
      w.stop = true;
    }
    w.wake.notify_all();
    w.thread.join();
    std::signal(SIGINT, previous_int_);
    std::signal(SIGTERM, previous_term_);
  }
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  void (*previous_int_)(int) = SIG_DFL;
  void (*previous_term_)(int) = SIG_DFL;
};

/// While one lives, `last_words(signal)` is what the watchdog does before it
/// ends an overdue run (write its summary); they must not throw.
class InterruptLastWords {
 public:
  explicit InterruptLastWords(std::function<void(int)> last_words) { set(std::move(last_words)); }
  ~InterruptLastWords() { set({}); }
  InterruptLastWords(const InterruptLastWords&) = delete;
  InterruptLastWords& operator=(const InterruptLastWords&) = delete;

 private:
  static void set(std::function<void(int)> words) {
    const std::lock_guard<std::mutex> lock(detail::watchdog().mutex);
    detail::watchdog().last_words = std::move(words);
  }
};

/// Throws Interrupted, saying where (the parts are joined), once a signal came.
template <class... Parts>
void stop_if_interrupted(const Parts&... where) {
  if (const int signal = detail::pending_signal) throw Interrupted(signal, detail::concat(where...));
}

}  // namespace kerf
