#pragma once
// The visibility criterion (Belytschko et al.): the cut is opaque; node I's
// weight at x is cut off (g = 0) when the straight segment from x_I to x
// crosses the cut, else untouched (g = 1). Its known flaw, kept on purpose:
// g jumps along the rays from a node through the cut's tips, so the shape
// functions are discontinuous in the body beyond the tips. A segment that only
// touches the cut at one of its two ends is not blocked. Nodes and points
// lying on the cut count as a hair off its +1 side (off_the_cut), where the
// grid places them, so they see one side only instead of gluing the faces.
#include "discretization/enrichment/enrichment_rule.h"

namespace kerf {

class VisibilityRule final : public EnrichmentRule {
 public:
  VisibilityRule(const CutSurface& cut, Index pieces, std::span<const Vec3> nodes, std::span<const double> support);

  bool enriches(Index node) const override { return enriched_[node]; }
  WeightFactor factor(Index node, const Vec3& x) const override;

 private:
  CutSurface cut_;
  Index pieces_;
  std::vector<Vec3> viewpoints_;  // the nodes, those on the cut moved off it (off_the_cut)
  std::vector<char> enriched_;
};

}  // namespace kerf
