#include "discretization/enrichment/phi_field_enrichment.h"

#include <limits>

namespace kerf {

PhiFieldEnrichment::PhiFieldEnrichment(const CutSurface& cut, Index pieces, Field field, std::span<const Vec3> nodes,
                                       std::span<const double> support)
    : cut_(cut), pieces_(pieces), field_(field) {
  frame_ = common_frame(cut_, 0, pieces_);
  if (field_ == Field::nearest_piece)
    for (Index k = 0; k < pieces_; ++k) piece_frame_.push_back(common_frame(cut_, k, k + 1));
  enriched_ = nodes_reached(cut_, pieces_, nodes, support);
  const Index n = static_cast<Index>(nodes.size());
  side_.assign(n, 1);
  nearest_.assign(n, 0);
  for (Index I = 0; I < n; ++I) {
    if (!enriched_[I]) continue;
    if (field_ == Field::nearest_piece) {
      double best = std::numeric_limits<double>::infinity();
      for (Index k = 0; k < pieces_; ++k) {
        const double d = distance_to_cut(cut_, k, k + 1, nodes[I]);
        if (d < best) best = d, nearest_[I] = k;
      }
    }
    side_[I] = phi(I, nodes[I]).value >= 0.0 ? 1 : -1;
  }
}

PhiValue PhiFieldEnrichment::phi(Index node, const Vec3& x) const {
  if (field_ == Field::grid) return grid_phi(cut_, 0, pieces_, frame_, x);
  const Index k = nearest_[node];
  return grid_phi(cut_, k, k + 1, piece_frame_[k], x);
}

WeightFactor PhiFieldEnrichment::factor(Index node, const Vec3& x) const {
  if (!enriched_[node]) return {};
  const PhiValue p = phi(node, x);
  return {0.5 * (1.0 + side_[node] * p.value), 0.5 * side_[node] * p.gradient};
}

}  // namespace kerf
