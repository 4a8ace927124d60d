#pragma once
// Barbieri's rule for one piece (rule `single`): node I is enriched by the
// phi of the one piece nearest to it, g_I(x) = (1 + sigma_I phi_k(x)) / 2,
// sigma_I = +1 or -1 the side of node I (phi(x_I) >= 0 is the + side).
#include "discretization/enrichment/cut_phi.h"
#include "discretization/enrichment/enrichment_rule.h"

namespace kerf {

class SinglePieceRule final : public EnrichmentRule {
 public:
  /// The cut's first `pieces` pieces (> 0), for these nodes; `support` is viewed: it must outlive this.
  SinglePieceRule(const CutSurface& cut, Index pieces, std::span<const Vec3> nodes, std::span<const double> support);

  bool enriches(Index node) const override { return enriched_[node]; }
  WeightFactor factor(Index node, const Vec3& x) const override;

 private:
  CutSurface cut_;
  std::vector<CutFrame> piece_frame_;  // each piece's own frame
  std::span<const double> support_;    // viewed: the nodes' support radii outlive the rule
  std::vector<char> enriched_;
  std::vector<signed char> side_;  // sigma_I
  std::vector<Index> nearest_;     // node I's piece
};

}  // namespace kerf
