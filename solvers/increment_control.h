#pragma once
// The size of the next increment (a static load increment, an implicit time
// step) from how the last ones went: halved when a solve fails, down to the
// first guess over 2^max_cutbacks, and doubled after an easy one, up to the
// first guess. A stepper walks from one output step to the next with it, so
// the output steps stay the scene's whatever increments the solves needed.
#include <algorithm>
#include <cmath>
#include <string>

#include "core/check.h"
#include "core/run_report.h"
#include "problem/scene.h"
#include "solvers/newton.h"

namespace kerf {

class IncrementControl {
 public:
  /// `first` is the scene's increment (1 / load_steps, or dt).
  IncrementControl(double first, const SolveOptions& options, RunReport& report)
      : first_(first), size_(first), adapt_(options.adapt), max_cutbacks_(options.max_cutbacks),
        easy_iterations_(std::max(1, options.newton.max_iterations / 4)), report_(report) {}

  struct Increment {
    double end;   // where the attempt ends
    double size;  // its length: the first exactly when it is the first (an unchanged dt refactorizes nothing)
  };
  /// The next attempt from `at`: one increment on, or to `to` when that is
  /// nearer (or so near that a sliver of an increment would be left).
  Increment next(double at, double to) const {
    const double remaining = to - at, sliver = 1e-9 * first_;
    if (size_ < remaining - sliver) return {at + size_, size_};
    return {to, std::abs(remaining - first_) <= sliver ? first_ : remaining};
  }
  /// An attempt of length `taken` converged.
  void accepted(double taken, const NewtonResult& result) {
    report_.solver.increments_taken += 1;
    SolverCounters::ConvergedBy& by = report_.solver.newton_converged_by;
    if (result.status == NewtonStatus::converged_relative) by.relative += 1;
    if (result.status == NewtonStatus::converged_absolute) by.absolute += 1;
    if (result.status == NewtonStatus::converged_step) by.step += 1;
    if (!report_.solver.smallest_increment || taken < *report_.solver.smallest_increment)
      report_.solver.smallest_increment = taken;
    if (result.iterations <= easy_iterations_) size_ = std::min(first_, 2.0 * size_);
  }
  /// The attempt from `at` to `end` failed (`why`): halves the increment, or
  /// throws naming `where` and why when adapting is off or the floor is passed.
  void rejected(double at, double end, const std::string& failure, const std::string& where) {
    // A failed factorization's message already starts with where it failed.
    const std::string said = failure.rfind(where, 0) == 0 ? failure : where + ": " + failure;
    KERF_CHECK_SHARED(adapt_, said, "; try a smaller time step, more load steps, more iterations, or "
               "solve.adapt: true (halves the increment when a solve fails)");
    const double floor = first_ * std::ldexp(1.0, -max_cutbacks_);
    KERF_CHECK_SHARED(0.5 * (end - at) >= floor * (1.0 - 1e-12), said, " from ", at, " to ", end,
               " after the increment was halved to ", end - at, " (", max_cutbacks_,
               " halvings of the first, solve.max_cutbacks); the problem may have no equilibrium there "
               "(a load past a limit point, a body not held), or needs more halvings");
    size_ = 0.5 * (end - at);
    report_.solver.cutbacks += 1;
  }

 private:
  double first_, size_;
  bool adapt_;
  int max_cutbacks_;
  int easy_iterations_;  // an attempt this quick lets the increment grow
  RunReport& report_;
};

}  // namespace kerf
