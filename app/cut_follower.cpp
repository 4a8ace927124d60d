#include "app/cut_follower.h"

#include "core/check.h"
#include "discretization/body_capabilities.h"
#include "discretization/body_factory.h"
#include "discretization/state_transfer.h"

namespace kerf {
namespace {

/// A growth's times: the body's update [start, updated], the solver side's refresh [updated, refreshed].
void record_growth(RunReport& report, double start, double updated, double refreshed) {
  report.cut_update_seconds.push_back(updated - start);
  report.cut_refresh_seconds.push_back(refreshed - updated);
  report.phases.add(Phase::cut_update, refreshed - start);
}

}  // namespace

CutFollower::CutFollower(const Scene& scene, SharedCuts cuts, const MpiContext& mpi)
    : scene_(scene), cuts_(std::move(cuts)), mpi_(mpi), pieces_(cuts_->pieces_at(0.0)) {}

bool CutFollower::follow(RunParts& run, SolverState& state, RunReport& report) {
  const Index now = cuts_->pieces_at(state.t);
  if (now == pieces_) return false;
  pieces_ = now;
  run.probes.reset();  // they refer to the body as it was
  if (auto* in_place = capability<CutsInShapeFunctions>(*run.body))
    update_rows(*in_place, run, state, report);
  else if (const auto* splitting = capability<CutsBySplitting>(*run.body); splitting && cuts_->grows_by_splitting())
    split_further(*splitting, run, state, report);
  else
    rebuild(run, state, report);
  return true;
}

void CutFollower::update_rows(CutsInShapeFunctions& body, RunParts& run, SolverState& state,
                              RunReport& report) const {
  const double start = now_seconds();
  const CutUpdate update = body.update_for_cuts(state.t);
  const double updated = now_seconds();
  run.mechanics->discretization_changed(update.changed_nodes);
  run.stepper->discretization_changed(state);
  record_growth(report, start, updated, now_seconds());
  report.cuts.updated_nodes += update.nodes;
  report.cuts.updated_points += update.points;
}

void CutFollower::rebuild(RunParts& run, SolverState& state, RunReport& report) const {
  const double start = now_seconds();
  RunReport rebuild_report;  // its setup phase is the cut update's, not the run's
  std::unique_ptr<DiscreteBody> body = make_body(scene_, cuts_, rebuild_report, state.t, mpi_);
  const MeshedBody* meshed = capability<MeshedBody>(*body);
  KERF_CHECK(meshed, "internal: a body that neither updates its cuts in place nor has a mesh cannot follow a cut");
  const StateTransfer transfer(*run.body, meshed->mesh());
  state.u = transfer(state.u);
  state.v = transfer(state.v);
  state.a = transfer(state.a);
  const Vector old_mode = run.stepper->vibration_mode();
  const Vector mode = old_mode.size() > 0 ? transfer(old_mode) : Vector();
  const double updated = now_seconds();
  replace_body(std::move(body), run, state, mode, report);
  record_growth(report, start, updated, now_seconds());
  report.cuts.removed_cells += rebuild_report.cuts.removed_cells;
  report.cuts.remeshes += 1;
  report.cuts.updated_nodes += run.body->node_count();
}

void CutFollower::split_further(const CutsBySplitting& splitting, RunParts& run, SolverState& state,
                                RunReport& report) const {
  const double start = now_seconds();
  std::unique_ptr<DiscreteBody> body = splitting.split_along(scene_, cuts_->fem_pieces(FemCut::split, state.t));
  state.u = splitting.carried_to(*body, state.u);
  state.v = splitting.carried_to(*body, state.v);
  state.a = splitting.carried_to(*body, state.a);
  const Vector old_mode = run.stepper->vibration_mode();
  const Vector mode = old_mode.size() > 0 ? splitting.carried_to(*body, old_mode) : Vector();
  const double updated = now_seconds();
  const Index added = body->node_count() - run.body->node_count();
  replace_body(std::move(body), run, state, mode, report);
  record_growth(report, start, updated, now_seconds());
  report.cuts.updated_nodes += added;
  record_split(*run.body, report);
}

void CutFollower::replace_body(std::unique_ptr<DiscreteBody> body, RunParts& run, SolverState& state,
                               const Vector& carried_mode, RunReport& report) const {
  run.stepper.reset();
  run.mechanics = std::make_unique<MechanicalSystem>(*body, scene_, report, mpi_.ranks);
  run.stepper = make_stepper(*run.mechanics, stepper_settings(scene_), report, carried_mode);
  run.stepper->discretization_changed(state);
  run.body = std::move(body);
}

}  // namespace kerf
