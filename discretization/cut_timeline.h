#pragma once
// A scene's cuts as they grow, built once per run (their geometry checked
// once: zero-length pieces, collapsed triangles, folds) and shared by every
// part of the run that needs them: the body factory (which pieces FEM meshes
// in or cuts out at time t), the meshless weights (CutWeights), the run loop
// (when new pieces appear) and the output (the cut surfaces and their opening).
#include <memory>
#include <vector>

#include "geometry/cut_surface.h"
#include "problem/scene.h"

namespace kerf {

class CutTimeline {
 public:
  /// Throws, naming the cut's scene line, when a cut is degenerate or folds.
  explicit CutTimeline(const Scene& scene);

  Index cut_count() const { return static_cast<Index>(cuts_.size()); }
  /// How the scene follows cut c: its enrichment rule, grid, FEM way.
  const Cut& settings(Index c) const { return cuts_[c]; }
  const CutSurface& surface(Index c) const { return surfaces_[c]; }
  /// Pieces of all the cuts present at time t (s): when this changes, the body must follow.
  Index pieces_at(double t) const;
  /// Does any piece appear after t = 0?
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
