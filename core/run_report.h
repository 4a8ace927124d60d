#pragma once
// What a run built, counted and how long each phase took: filled by every
// layer, written to summary.json (app/summary_json.h), so a test can check that
// a scene got only what it needs and a study can compare methods phase by
// phase. Typed fields for what every run has; `extras` for figures only some
// methods have.
#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/timer.h"
#include "core/types.h"

namespace kerf {

/// The discretization's size (summary "counts").
struct RunCounts {
  Index nodes = 0, dofs = 0;
  Index elements = 0;           // cells (FEM) or integration points (meshless)
  double neighbors_mean = 0.0;  // other nodes a node is coupled to
};

/// A rank's peak resident memory (MB) at the run's milestones.
struct MemoryMarks {
  double after_body = 0.0;            // mesh or nodes, shape functions, the matrix pattern
  double after_initialization = 0.0;  // and the first assembly, factorization or preconditioner
  double at_end = 0.0;                // and the step loop, output included
};

/// How the MPI ranks shared the run (summary "parallel"), as rank 0 saw it.
struct RankCounts {
  int ranks = 1;
  bool partitioned = false;  // each rank assembled its own cells (else every rank the whole)
  bool mesh_divided = false; // each rank held its piece of the mesh (else every rank the whole mesh)
  bool state_in_pieces = false;  // an explicit step's vectors were each rank's piece, only ghosts exchanged
  Index owned_rows = 0;      // rank 0's rows
  Index touched_rows = 0;    // rows rank 0 computes values in: its own and its ghosts'
  MemoryMarks memory;                       // this rank's (the summary: rank 0's)
  std::vector<MemoryMarks> memory_by_rank;  // every rank's, gathered when the run ended well
};

/// The solvers' work over the run (summary "solver"; zero when a run had none).
struct SolverCounters {
  long factorizations = 0;         // numeric factorizations or preconditioner set-ups
  long linear_iterations = 0;      // iterations of iterative linear solves
  long pcg_iterations = 0;         // CG iterations preconditioned by a stale factor
  long newton_iterations = 0;      // Newton's linear solves, summed over the steps
  long contact_augmentations = 0;  // augmented Lagrangian rounds (static contact)
  long definite_tangent_fallbacks = 0;  // factorizations of the exact tangent that failed and took the definite one
  long increments_taken = 0;  // static load increments or implicit time steps solved (adaptive: with the cut ones)
  long cutbacks = 0;          // increments halved after a failed Newton solve
  std::optional<double> smallest_increment;  // load factor or s
  struct ConvergedBy {
    long relative = 0, absolute = 0, step = 0;  // Newton solves ended by each test
  } newton_converged_by;
  std::optional<double> critical_dt_s;                // central differences: the stable step (s)
  std::optional<double> critical_dt_element_bound_s;  // FEM's element-by-element bound (s)
  std::optional<double> critical_dt_min_s;  // the smallest estimate after a cut grew (central differences)
  int substeps_max = 1;                     // the most substeps a step took after a growth lowered the estimate
};

/// What growing cuts (and cut-out cells) did to the discretization.
struct CutCounters {
  long remeshes = 0;        // FEM bodies meshed again
  long removed_cells = 0;   // cells deleted (fem: remove), over every mesh built
  long updated_nodes = 0;   // nodes whose shape functions changed, summed over the growths
  long updated_points = 0;  // integration points recomputed, summed over the growths
  // fem: split, in the body as it stands:
  long split_cells = 0;        // cells the cut separates (each replaced by one copy per side)
  long duplicated_nodes = 0;   // nodes added as copies
  double dropped_volume = 0.0; // m^3 (2D: m^2) of fragments too small to keep (split_elements.md 3.4)
  // fem.split_front: subdivide:
  long front_points = 0;        // points of the front inserted into the mesh, over every growth
  long front_unresolved = 0;    // front segments not made edges, in the body as it stands (the jump lags there)
};

struct RunReport {
  double setup_seconds = 0.0;  // wall time before the first step: body, stepper, initial state
  double solve_seconds = 0.0;  // wall time of the steps (each with its cut update and output)
  PhaseTimes phases;
  std::vector<std::string> stages;   // mesh, mass, stiffness, factorization, petsc, vtk, ...
  RunCounts counts;
  RankCounts parallel;
  SolverCounters solver;
  CutCounters cuts;
  std::vector<double> step_seconds;         // wall time of each time step (or load step)
  std::vector<double> cut_update_seconds;   // per growth of a cut: the body's update (enrichment, shapes)
  std::vector<double> cut_refresh_seconds;  // per growth: the stepper re-reading mass, forces, factors
  std::map<std::string, double> extras;     // method-specific figures (meshless: mls_condition_*)
  /// What the run did differently from the scene's words and why (a mesh
  /// file's order raised or lowered to the element asked): summary "notes".
  std::vector<std::string> notes;

  void add_stage(const std::string& stage) {
    if (std::find(stages.begin(), stages.end(), stage) == stages.end()) stages.push_back(stage);
  }
};

}  // namespace kerf
