#pragma once
// The one place that decides how a run follows its growing cuts. After each
// step, when the timeline says pieces appeared by the state's time, either
//   - the body carries its cuts in its shape functions (meshless nodal
//     integration): it recomputes the rows the new pieces touch in place, the
//     dofs stay, and the stepper re-reads what it keeps (mass, forces,
//     factors); or
//   - its cuts split its cells (FEM, fem: split): the same mesh is split
//     along the pieces as they stand, the state copied exactly onto the new
//     copies (nothing interpolated), and the mechanical system and stepper
//     are made again on it; or
//   - neither (FEM): a new body is built with the cuts as they stand
//     (meshed in, or more cells removed), the state (u, v, a) is carried onto
//     its mesh, and the mechanical system and stepper are made again on it.
// Each growth is timed (cut_update_ms: the body's update; cut_refresh_ms: the
// solver side re-reading it) and counted in the report.
#include "app/run_parts.h"
#include "core/mpi_context.h"
#include "discretization/cut_timeline.h"

namespace kerf {

class CutFollower {
 public:
  /// `mpi`: the run's ranks, for the bodies it builds again.
  CutFollower(const Scene& scene, SharedCuts cuts, const MpiContext& mpi = {});

  /// Brings the run up to the cuts at state.t. True when the body changed:
  /// the probes are then gone (null) and must be resolved again.
  bool follow(RunParts& run, SolverState& state, RunReport& report);

 private:
  void update_rows(CutsInShapeFunctions& body, RunParts& run, SolverState& state, RunReport& report) const;
  void rebuild(RunParts& run, SolverState& state, RunReport& report) const;
  void split_further(const CutsBySplitting& body, RunParts& run, SolverState& state, RunReport& report) const;
  /// The mechanical system and stepper made again on the new body, which takes the run's place.
  /// carried_mode: the old stepper's vibration mode carried to `body` (empty: none).
  void replace_body(std::unique_ptr<DiscreteBody> body, RunParts& run, SolverState& state, const Vector& carried_mode,
                    RunReport& report) const;

  const Scene& scene_;
  SharedCuts cuts_;
  MpiContext mpi_;
  Index pieces_;  // present when the body was last brought up to date
};

}  // namespace kerf
