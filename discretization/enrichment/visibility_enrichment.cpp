#include "discretization/enrichment/visibility_enrichment.h"

namespace kerf {

VisibilityEnrichment::VisibilityEnrichment(const CutSurface& cut, Index pieces, std::span<const Vec3> nodes,
                                           std::span<const double> support)
    : cut_(cut), pieces_(pieces), nodes_(nodes.begin(), nodes.end()) {
  enriched_ = nodes_reached(cut_, pieces_, nodes, support);
}

WeightFactor VisibilityEnrichment::factor(Index node, const Vec3& x) const {
  if (!enriched_[node]) return {};
  if (!segment_crosses_cut(cut_, 0, pieces_, nodes_[node], x)) return {};
  return {0.0, Vec3::Zero()};
}

}  // namespace kerf
