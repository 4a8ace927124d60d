#pragma once
// One run of a scene, end to end: discretize, step, observe, write results.
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "core/mpi_context.h"
#include "core/run_report.h"
#include "discretization/body_snapshot.h"
#include "discretization/cut_timeline.h"
#include "problem/scene.h"

namespace kerf {

struct RunOptions {
  std::string out_dir;  // overrides output.dir when not empty
  bool quiet = false;
  MpiContext mpi{};  // under mpirun: rank 0 writes the files, every rank its piece of the ParaView series
  bool writes_files() const { return mpi.ranks.rank == 0; }
  bool force = false;  // run even when the resource estimate says the run cannot fit in memory
  bool keep_final_body = false;  // RunOutcome::final_body (the Python module's arrays)
};

struct RunOutcome {
  std::string directory;
  nlohmann::ordered_json summary;  // as written to summary.json
  RunReport report;                // the same figures, typed
  /// The body at the end, as ParaView gets it (reference points, the point
  /// fields: displacement, stresses); with RunOptions::keep_final_body.
  std::shared_ptr<const BodySnapshot> final_body;
};

/// Refuses, before any work, what the scene asks for that cannot run
/// (validate(), then the cuts' geometry: degenerate or folding cuts); returns
/// the cut timeline the run shares (a session extends it, the rest read it).
std::shared_ptr<CutTimeline> refuse_unrunnable(const Scene& scene);

/// Writes summary.json (status "ok"), probes.csv and the ParaView series.
/// On failure, writes summary.json with status "error" and the message, keeps
/// every file already written, and rethrows; on an MPI rank other than 0 it
/// stops every rank instead (stop_every_rank), writing the summary itself if
/// rank 0 did not stop the job first.
RunOutcome run_scene(const Scene& scene, const RunOptions& options = {});

}  // namespace kerf
