#include "app/run_observer.h"

#include "discretization/body_capabilities.h"
#include "discretization/cut_snapshot.h"
#include "solvers/petsc_session.h"

namespace kerf {
namespace {

std::vector<std::string> table_columns(const ProbeSet& probes) {
  std::vector<std::string> columns = probes.columns();
  columns.insert(columns.begin(), "time");
  return columns;
}

}  // namespace

RunObserver::RunObserver(const Scene& scene, const std::string& directory, SharedCuts cuts, const ProbeSet& probes,
                         RankShare ranks)
    : cuts_(std::move(cuts)), writes_files_(ranks.rank == 0) {
  if (scene.output.vtk_every > 0)
    vtk_ = std::make_unique<VtkSeries>(directory, scene.name, ranks, ranks.distributed() ? wait_for_every_rank : nullptr);
  if (writes_files_) table_.emplace(directory + "/probes.csv", table_columns(probes));
}

void RunObserver::reset_loads(const RunParts& run, const SolverState& state) {
  if (run.probes->needs_energy()) run.stepper->applied_load(state, load_before_);
}

void RunObserver::before_step(const RunParts& run, SolverState& state) {
  if (!run.probes->needs_energy()) return;
  run.stepper->complete_state(state);
  u_before_ = state.u;
}

void RunObserver::after_step(const RunParts& run, SolverState& state) {
  // Before a cut changes the dofs' meaning: the work over this step.
  if (!run.probes->needs_energy()) return;
  run.stepper->complete_state(state);
  run.stepper->applied_load(state, load_after_);
  energy_.external_work += 0.5 * (load_before_ + load_after_).dot(state.u - u_before_);
  load_before_.swap(load_after_);
}

void RunObserver::evaluate(const RunParts& run, SolverState& state) {
  const ProbeSet& probes = *run.probes;
  if (const auto& read = probes.displacement_dofs_read(); read && !vtk_)
    run.stepper->complete_displacement_at(state, *read);
  else
    run.stepper->complete_state(state);
  if (probes.needs_reaction()) reaction_ = run.stepper->reaction(state);
  if (probes.needs_energy()) {
    energy_.kinetic = run.stepper->kinetic_energy(state);
    energy_.strain = run.mechanics->strain_energy(state.u);
  }
}

void RunObserver::write(const RunParts& run, SolverState& state, std::size_t growths, RunReport& report) {
  ScopedTimer timer(report.phases, Phase::output);
  evaluate(run, state);
  std::vector<double> row = run.probes->values(state, reaction_, energy_);
  row.insert(row.begin(), state.t);
  if (table_) table_->append(row);
  if (vtk_) {
    const Vector& u = run.mechanics->body_part(state.u, body_u_);
    BodySnapshot body, cut;
    run.body->snapshot(u, body);
    std::vector<LatticeSnapshot> lattices;
    const bool grids_changed = growths != lattices_written_at_;
    // Every rank: the cut's displacements ask the body where its points are,
    // a collective call when the mesh is divided among the ranks.
    cut_snapshot(*cuts_, state.t, *run.body, u, cut);
    if (writes_files_) {  // the other ranks write only their piece of the body
      if (const auto* grids = capability<EnrichmentLattices>(*run.body); grids && grids_changed)
        lattices = grids->enrichment_lattices();
    }
    vtk_->write(body, state.t, &cut, grids_changed ? &lattices : nullptr);
    lattices_written_at_ = growths;
    report.add_stage("vtk");
  }
}

nlohmann::ordered_json RunObserver::final_probes(const RunParts& run, const SolverState& state) const {
  return run.probes->final_values(state, reaction_, energy_);
}

nlohmann::ordered_json RunObserver::probes_now(const RunParts& run, SolverState& state) {
  evaluate(run, state);
  return final_probes(run, state);
}

}  // namespace kerf
