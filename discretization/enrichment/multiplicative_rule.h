#pragma once
// Barbieri's rule for several pieces (paper eq. 18), kept because the paper
// shows it fails at kinks (Fig. 7): g_I(x) = prod_k (1 + sigma_Ik phi_k(x)) / 2
// over the pieces k that node I's support reaches, phi_k the piece's own
// function and sigma_Ik node I's side of it.
#include "discretization/enrichment/cut_phi.h"
#include "discretization/enrichment/enrichment_rule.h"

namespace kerf {

class MultiplicativeRule final : public EnrichmentRule {
 public:
  /// `support` is viewed: it must outlive this.
  MultiplicativeRule(const CutSurface& cut, Index pieces, std::span<const Vec3> nodes, std::span<const double> support);

  bool enriches(Index node) const override { return start_[node + 1] > start_[node]; }
  WeightFactor factor(Index node, const Vec3& x) const override;

 private:
  CutSurface cut_;
  std::vector<CutFrame> frame_;  // per piece
  std::span<const double> support_;  // viewed: the nodes' support radii outlive the rule
  std::vector<Index> start_;     // CSR over nodes: the pieces each node reaches
  std::vector<Index> piece_;
  std::vector<signed char> side_;  // per (node, piece)
};

}  // namespace kerf
