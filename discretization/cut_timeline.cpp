#include "discretization/cut_timeline.h"

#include <algorithm>
#include <string>

#include "core/check.h"

namespace kerf {

CutTimeline::CutTimeline(const Scene& scene) : cuts_(scene.cuts) {
  for (const Cut& c : cuts_) surfaces_.push_back(cut_surface(scene.dimension, c.vertices, c.times, c.where.describe()));
}

// A fed cut stays live, and a scripted one keeps its times: whether a cut grows is fixed by the scene.
bool CutTimeline::grows() const {
  return std::any_of(cuts_.begin(), cuts_.end(), [](const Cut& c) { return c.grows(); });
}

void CutTimeline::extend(Index c, std::span<const Vec3> vertices, double time) {
  KERF_CHECK(c >= 0 && c < cut_count(), "cut ", c, " does not exist: the scene has ", cut_count(), " cut(s)");
  Cut& cut = cuts_[c];
  const std::string key = "cuts." + std::to_string(c);
  KERF_CHECK(cut.live, key, ".live: the cut is not declared live, so the run was set up for its scene's vertices "
             "alone; expected live: true in the scene to feed it at run time");
  KERF_CHECK(!vertices.empty(), key, ": no vertex to extend the cut by");
  surfaces_[c].where = cut.where.describe() + " (" + key + ", fed at run time)";
  extend_cut_surface(surfaces_[c], vertices, time);
  cut.vertices.insert(cut.vertices.end(), vertices.begin(), vertices.end());
  cut.times.resize(cut.vertices.size(), time);
}

Index CutTimeline::pieces_at(double t) const {
  Index count = 0;
  for (const CutSurface& s : surfaces_) count += s.pieces_at(t);
  return count;
}

bool CutTimeline::grows_by_splitting() const {
  bool any = false;
  for (std::size_t c = 0; c < cuts_.size(); ++c) {
    if (!cuts_[c].grows()) continue;
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
