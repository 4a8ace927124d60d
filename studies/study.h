#pragma once
// The studies behind `kerf study NAME`: each one a function in its own file
// here, reading like a worked example (what it solves, then numbered steps),
// writing CSV, JSON and PNG plots to its output folder, and checking its
// headline claim: a claim that fails is an error (exit code 1), so each
// study's --quick mode is a test.
#include <span>
#include <string>

namespace kerf {

struct StudyOptions {
  bool quick = false;   // the short version the tests run
  std::string out_dir;  // results/<study> unless given
  bool quiet = false;   // no progress lines
};

struct StudyEntry {
  const char* name;
  const char* summary;  // one line for `kerf study` without a name
  void (*run)(const StudyOptions&);
};

/// Every study, in the order `make run` runs them.
std::span<const StudyEntry> all_studies();

/// Runs the study `name`; throws naming the known studies when there is none.
void run_study(const std::string& name, StudyOptions options);

void hertz_study(const StudyOptions& options);
void timing_study(const StudyOptions& options);
void stability_study(const StudyOptions& options);
void pareto_study(const StudyOptions& options);
void cut_study(const StudyOptions& options);
void cut_convergence_study(const StudyOptions& options);
void crack3d_study(const StudyOptions& options);
void organ_study(const StudyOptions& options);
void solvers_study(const StudyOptions& options);
void scaling_study(const StudyOptions& options);
void haptic_study(const StudyOptions& options);

}  // namespace kerf
