#include "discretization/cut_timeline.h"

#include <algorithm>

namespace kerf {

CutTimeline::CutTimeline(const Scene& scene) : cuts_(scene.cuts) {
  for (const Cut& c : cuts_) surfaces_.push_back(cut_surface(scene.dimension, c.vertices, c.times, c.where.describe()));
}

Index CutTimeline::pieces_at(double t) const {
  Index count = 0;
  for (const CutSurface& s : surfaces_) count += s.pieces_at(t);
  return count;
}

bool CutTimeline::grows() const {
  return std::any_of(surfaces_.begin(), surfaces_.end(), [](const CutSurface& s) { return s.appears.back() > 0.0; });
}

bool CutTimeline::grows_by_splitting() const {
  bool any = false;
  for (std::size_t c = 0; c < cuts_.size(); ++c) {
    if (surfaces_[c].appears.back() <= 0.0) continue;
    if (cuts_[c].fem != FemCut::split) return false;
    any = true;
  }
  return any;
}

std::vector<CutPiece> CutTimeline::fem_pieces(FemCut way, double t) const {
  std::vector<CutPiece> out;
  for (std::size_t c = 0; c < cuts_.size(); ++c)
    if (cuts_[c].fem == way)
      out.insert(out.end(), surfaces_[c].pieces.begin(), surfaces_[c].pieces.begin() + surfaces_[c].pieces_at(t));
  return out;
}

}  // namespace kerf
