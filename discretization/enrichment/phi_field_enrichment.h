#pragma once
// Enrichment through one scalar field phi of the cut: g_I(x) = (1 + sigma_I phi(x)) / 2,
// sigma_I = +1 or -1 the side of node I (phi(x_I) >= 0 is the + side). The
// field is the Enrichment Grid's phi of the whole cut (rule `grid`, exact
// lookup), or Barbieri's phi of the one piece nearest to node I (rule `single`).
#include "discretization/enrichment/cut_phi.h"
#include "discretization/enrichment/weight_enrichment.h"

namespace kerf {

class PhiFieldEnrichment final : public WeightEnrichment {
 public:
  enum class Field { grid, nearest_piece };
  /// The cut's first `pieces` pieces (> 0), for these nodes.
  PhiFieldEnrichment(const CutSurface& cut, Index pieces, Field field, std::span<const Vec3> nodes,
                     std::span<const double> support);

  bool enriches(Index node) const override { return enriched_[node]; }
  WeightFactor factor(Index node, const Vec3& x) const override;

 private:
  PhiValue phi(Index node, const Vec3& x) const;

  CutSurface cut_;
  Index pieces_;
  Field field_;
  CutFrame frame_;                    // grid: the common frame of the pieces
  std::vector<CutFrame> piece_frame_; // nearest_piece: each piece's own frame
  std::vector<char> enriched_;
  std::vector<signed char> side_;     // sigma_I
  std::vector<Index> nearest_;        // nearest_piece: node I's piece
};

}  // namespace kerf
