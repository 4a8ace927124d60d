#pragma once
// What a run built and how long each phase took: filled by every layer,
// written to summary.json, so a test can check that a scene got only what it needs.
#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "core/timer.h"

namespace kerf {

struct RunReport {
  PhaseTimes phases;                 // setup, assembly, factorize, solve, cut_update, output
  std::vector<std::string> stages;   // mesh, mass, stiffness, factorization, petsc, vtk, ...
  std::vector<double> step_seconds;  // wall time of each time step (or load step)
  std::vector<double> cut_update_seconds;   // per growth of a cut: the body's update (enrichment, shapes)
  std::vector<double> cut_refresh_seconds;  // per growth: the stepper re-reading mass, forces, factors
  std::map<std::string, double> counters;  // e.g. factorizations, pcg_iterations

  void add_stage(const std::string& stage) {
    if (std::find(stages.begin(), stages.end(), stage) == stages.end()) stages.push_back(stage);
  }
};

}  // namespace kerf
