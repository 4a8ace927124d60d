#include "discretization/enrichment/single_piece_rule.h"

#include <limits>

namespace kerf {

SinglePieceRule::SinglePieceRule(const CutSurface& cut, Index pieces, std::span<const Vec3> nodes,
                                 std::span<const double> support)
    : cut_(cut), support_(support) {
  for (Index k = 0; k < pieces; ++k) piece_frame_.push_back(common_frame(cut_, k, k + 1));
  enriched_ = nodes_reached(cut_, pieces, nodes, support);
  const Index n = static_cast<Index>(nodes.size());
  side_.assign(n, 1);
  nearest_.assign(n, 0);
  for (Index I = 0; I < n; ++I) {
    if (!enriched_[I]) continue;
    double best = std::numeric_limits<double>::infinity();
    for (Index k = 0; k < pieces; ++k) {
      const double d = distance_to_cut(cut_, k, k + 1, nodes[I]);
      if (d < best) best = d, nearest_[I] = k;
    }
    side_[I] = grid_phi(cut_, nearest_[I], nearest_[I] + 1, piece_frame_[nearest_[I]], nodes[I]).value >= 0.0 ? 1 : -1;
  }
}

WeightFactor SinglePieceRule::factor(Index node, const Vec3& x) const {
  if (!enriched_[node]) return {};
  const Index k = nearest_[node];
  return side_factor(grid_phi(cut_, k, k + 1, piece_frame_[k], x), side_[node], support_[node]);
}

}  // namespace kerf
