#pragma once
// The diffraction criterion (Organ et al. 1996): when the segment from node I
// to x crosses the cut, the weight's distance is the length of the shortest
// path that bends around the cut's free edge (2D: around a tip; 3D: around a
// point of the strip's boundary), d = |x_I - c| + |c - x|, so node I sees
// around the tip with a weight that fades with the bent path:
// g_I(x) = w(d / d_I) / w(|x - x_I| / d_I). The edge point c is held fixed in
// the gradient (it minimises d, so d's gradient is (x - c) / |x - c|). Nodes
// and points lying on the cut count as a hair off its +1 side (off_the_cut).
#include "discretization/enrichment/enrichment_rule.h"

namespace kerf {

class DiffractionRule final : public EnrichmentRule {
 public:
  DiffractionRule(const CutSurface& cut, Index pieces, std::span<const Vec3> nodes, std::span<const double> support);

  bool enriches(Index node) const override { return enriched_[node]; }
  WeightFactor factor(Index node, const Vec3& x) const override;

 private:
  /// The point of the cut's free edge on the shortest path from a to b around it.
  Vec3 bend_point(const Vec3& a, const Vec3& b) const;

  CutSurface cut_;
  Index pieces_;
  std::vector<Vec3> nodes_;
  std::vector<Vec3> viewpoints_;  // the nodes, those on the cut moved off it (off_the_cut)
  std::vector<double> support_;
  std::vector<char> enriched_;
  std::vector<std::array<Vec3, 2>> edges_;  // the free edge: 2D two tips (as points), 3D boundary edges
};

}  // namespace kerf
