#include "discretization/enrichment/multiplicative_rule.h"

namespace kerf {

MultiplicativeRule::MultiplicativeRule(const CutSurface& cut, Index pieces, std::span<const Vec3> nodes,
                                       std::span<const double> support)
    : cut_(cut), support_(support) {
  for (Index k = 0; k < pieces; ++k) frame_.push_back(common_frame(cut_, k, k + 1));
  const Index n = static_cast<Index>(nodes.size());
  start_.assign(1, 0);
  for (Index I = 0; I < n; ++I) {
    for (Index k = 0; k < pieces; ++k) {
      if (distance_to_cut(cut_, k, k + 1, nodes[I]) >= support[I]) continue;
      piece_.push_back(k);
      side_.push_back(grid_phi(cut_, k, k + 1, frame_[k], nodes[I]).value >= 0.0 ? 1 : -1);
    }
    start_.push_back(static_cast<Index>(piece_.size()));
  }
}

WeightFactor MultiplicativeRule::factor(Index node, const Vec3& x) const {
  WeightFactor g;
  for (Index j = start_[node]; j < start_[node + 1]; ++j) {
    const Index k = piece_[j];
    g = g * side_factor(grid_phi(cut_, k, k + 1, frame_[k], x), side_[j], support_[node]);
  }
  return g;
}

}  // namespace kerf
