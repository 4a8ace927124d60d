#pragma once
// A scene's cuts as they grow, built once per run (their geometry checked
// once: zero-length pieces, collapsed triangles, folds) and shared by every
// part of the run that needs them: the body factory (which pieces FEM meshes
// in or cuts out at time t), the meshless weights (CutWeights), the run loop
// (when new pieces appear) and the output (the cut surfaces and their opening).
#include <memory>
#include <span>
#include <vector>

#include "geometry/cut_surface.h"
#include "problem/scene.h"

namespace kerf {

class CutTimeline {
 public:
  /// Throws, naming the cut's scene line, when a cut is degenerate or folds.
  explicit CutTimeline(const Scene& scene);

  /// Appends `vertices` to cut c at `time` (s): the next polyline vertex, or
  /// the next vertex pair of a strip (a blade's two ends), fed as the run
  /// goes. The pieces they complete appear at `time`, as if the scene had
  /// given the vertices with that time. Throws, leaving the cut as it was,
  /// when `time` is before the cut's last vertex or a new piece is degenerate
  /// or folds the cut. The parts of a run holding the timeline see the new
  /// pieces (Session::extend_cut).
  void extend(Index c, std::span<const Vec3> vertices, double time);

  Index cut_count() const { return static_cast<Index>(cuts_.size()); }
  /// How the scene follows cut c: its enrichment rule, grid, FEM way.
  const Cut& settings(Index c) const { return cuts_[c]; }
  const CutSurface& surface(Index c) const { return surfaces_[c]; }
  /// Pieces of all the cuts present at time t (s): when this changes, the body must follow.
  Index pieces_at(double t) const;
  /// Does any piece appear after t = 0 (or is any cut fed at run time)? Fixed from the scene.
  bool grows() const;
  /// The pieces present at time t of the cuts FEM follows in `way`.
  std::vector<CutPiece> fem_pieces(FemCut way, double t) const;
  /// Does every cut that grows split FEM's cells (fem: split)? Then a growth
  /// splits the same mesh further instead of meshing the body anew.
  bool grows_by_splitting() const;

 private:
  std::vector<Cut> cuts_;
  std::vector<CutSurface> surfaces_;
};

/// The timeline every part of a run shares (never null; empty without cuts).
using SharedCuts = std::shared_ptr<const CutTimeline>;

}  // namespace kerf
