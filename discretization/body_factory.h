#pragma once
// Scene -> discretized body: meshes the domain (or reads the mesh) and builds
// the method the scene asks for. Records the stages it builds in the report.
#include <memory>

#include "core/mpi_context.h"
#include "core/run_report.h"
#include "discretization/cut_timeline.h"
#include "discretization/discrete_body.h"

namespace kerf {

/// FEM takes the cuts' pieces present at `time` (s): those meshed in
/// (`fem: remesh`), whose cells are removed (`fem: remove`) or split
/// (`fem: split`); the meshless
/// methods enrich their weights with the cuts as they grow. Contact is not
/// the body's: solvers/mechanical_system.h adds it. Under mpirun (`mpi`
/// distributed), rank 0 alone meshes and the body computes its rank's part.
std::unique_ptr<DiscreteBody> make_body(const Scene& scene, SharedCuts cuts, RunReport& report, double time = 0.0,
                                        const MpiContext& mpi = {});
/// The same, serial, building the scene's cut timeline on the way (tests, studies).
std::unique_ptr<DiscreteBody> make_body(const Scene& scene, RunReport& report);

/// What a split by `fem: split` did to a FEM body as it stands (cells split,
/// nodes added, volume dropped), into the report; nothing for other bodies.
void record_split(const DiscreteBody& body, RunReport& report);

}  // namespace kerf
