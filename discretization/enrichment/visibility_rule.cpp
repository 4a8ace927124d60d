#include "discretization/enrichment/visibility_rule.h"

namespace kerf {

VisibilityRule::VisibilityRule(const CutSurface& cut, Index pieces, std::span<const Vec3> nodes,
                               std::span<const double> support)
    : cut_(cut), pieces_(pieces), viewpoints_(nodes.begin(), nodes.end()) {
  enriched_ = nodes_reached(cut_, pieces_, nodes, support);
  for (std::size_t I = 0; I < viewpoints_.size(); ++I)
    if (enriched_[I]) viewpoints_[I] = off_the_cut(cut_, pieces_, viewpoints_[I]);
}

WeightFactor VisibilityRule::factor(Index node, const Vec3& x) const {
  if (!enriched_[node]) return {};
  if (!segment_crosses_cut(cut_, 0, pieces_, viewpoints_[node], off_the_cut(cut_, pieces_, x))) return {};
  return {0.0, Vec3::Zero()};
}

}  // namespace kerf
