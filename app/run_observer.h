#pragma once
// What a run writes as it goes: a probes.csv row every output step, the
// ParaView series (the body, the cuts with their opening, the Enrichment
// Grids' phi when a cut grew since they were last written), and the work the
// loads did step by step for the energy probe.
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/run_parts.h"
#include "discretization/cut_timeline.h"
#include "output/probe_table.h"
#include "output/vtk_series.h"

namespace kerf {

class RunObserver {
 public:
  /// Opens probes.csv (its columns from `probes`) and, when the scene asks
  /// for ParaView output, the series, in `directory`. Across `ranks`, rank 0
  /// writes them and every rank its piece of the body's series; the others
  /// evaluate the same probes and write nothing else.
  RunObserver(const Scene& scene, const std::string& directory, SharedCuts cuts, const ProbeSet& probes,
              RankShare ranks = {});

  /// The loads the next step starts from: at the start, and after a cut
  /// changed the discretization (the loads as the new one integrates them).
  void reset_loads(const RunParts& run, const SolverState& state);
  /// Around each step: the trapezoidal work of the applied loads over it.
  /// Collective with the energy probe (they complete the state).
  void before_step(const RunParts& run, SolverState& state);
  void after_step(const RunParts& run, SolverState& state);

  /// A probes.csv row and, with ParaView output, the snapshots; `growths`:
  /// the cut growths so far.
  /// Collective: the state is completed where they read it (Stepper::complete_state).
  void write(const RunParts& run, SolverState& state, std::size_t growths, RunReport& report);
  /// The probes' values at the last write, as summary.json holds them.
  nlohmann::ordered_json final_probes(const RunParts& run, const SolverState& state) const;
  /// The same at the state as it is now, written or not. Collective, as write().
  nlohmann::ordered_json probes_now(const RunParts& run, SolverState& state);

 private:
  /// The state completed where the probes (and the series) read it, the reaction and energies now.
  void evaluate(const RunParts& run, SolverState& state);

  SharedCuts cuts_;
  bool writes_files_;
  std::unique_ptr<VtkSeries> vtk_;
  std::optional<ProbeTable> table_;
  EnergyState energy_;
  std::size_t lattices_written_at_ = static_cast<std::size_t>(-1);  // growths when the grids were last written
  Vector reaction_, load_before_, load_after_, u_before_, body_u_;
};

}  // namespace kerf
