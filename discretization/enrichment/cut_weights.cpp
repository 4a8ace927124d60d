#include "discretization/enrichment/cut_weights.h"

#include <algorithm>

#include "core/check.h"
#include "discretization/enrichment/diffraction_rule.h"
#include "discretization/enrichment/grid_rule.h"
#include "discretization/enrichment/multiplicative_rule.h"
#include "discretization/enrichment/single_piece_rule.h"
#include "discretization/enrichment/visibility_rule.h"

namespace kerf {

CutWeights::CutWeights(std::span<const Cut> cuts, std::vector<CutSurface> surfaces, std::span<const Vec3> nodes,
                       std::span<const double> support, const PointIndex& index, double time)
    : nodes_(nodes.begin(), nodes.end()), support_(support.begin(), support.end()), index_(index) {
  KERF_CHECK(cuts.size() == surfaces.size(), "one surface per cut expected");
  if (!support.empty()) largest_support_ = *std::max_element(support.begin(), support.end());
  for (std::size_t c = 0; c < cuts.size(); ++c) parts_.push_back(Part{cuts[c], std::move(surfaces[c]), 0, nullptr});
  advance_to(time);
}

CutWeights::~CutWeights() = default;

bool CutWeights::present() const {
  return std::any_of(parts_.begin(), parts_.end(), [](const Part& p) { return p.pieces > 0; });
}

bool CutWeights::enriches(Index node) const {
  for (const Part& p : parts_)
    if (p.rule && p.rule->enriches(node)) return true;
  return false;
}

WeightFactor CutWeights::factor(Index node, const Vec3& x) const {
  WeightFactor g;
  for (const Part& p : parts_)
    if (p.rule && p.rule->enriches(node)) g = g * p.rule->factor(node, x);
  return g;
}

std::vector<Index> CutWeights::reached_by(const CutSurface& surface, Index first, Index last) const {
  std::vector<Index> out, candidates;
  for (Index k = first; k < last; ++k) {
    const CutPiece& piece = surface.pieces[k];
    double radius = 0.0;
    for (int c = 0; c < surface.dimension; ++c) radius = std::max(radius, (piece.corner[c] - piece.centre).norm());
    index_.within(piece.centre, radius + largest_support_, candidates);
    for (Index I : candidates)
      if (distance_to_cut(surface, k, k + 1, nodes_[I]) < support_[I]) out.push_back(I);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::unique_ptr<EnrichmentRule> CutWeights::make_rule(const Part& part, std::span<const Index> reached) const {
  const CutSurface& s = part.surface;
  switch (part.cut.enrichment) {
    case Enrichment::grid:
      return std::make_unique<GridRule>(s, part.pieces, part.cut.grid_spacing, part.cut.grid_lookup, nodes_, support_,
                                        reached);
    case Enrichment::single:
      return std::make_unique<SinglePieceRule>(s, part.pieces, nodes_, support_);
    case Enrichment::multiplicative:
      return std::make_unique<MultiplicativeRule>(s, part.pieces, nodes_, support_);
    case Enrichment::visibility:
      return std::make_unique<VisibilityRule>(s, part.pieces, nodes_, support_);
    case Enrichment::diffraction:
      return std::make_unique<DiffractionRule>(s, part.pieces, nodes_, support_);
  }
  return nullptr;
}

std::vector<Index> CutWeights::advance_to(double t) {
  std::vector<Index> changed;
  for (Part& part : parts_) {
    const Index now = part.surface.pieces_at(t);
    if (now <= part.pieces) continue;
    const Index before = part.pieces;
    part.pieces = now;
    const std::vector<Index> reached = reached_by(part.surface, before, now);
    if (auto* grid = dynamic_cast<GridRule*>(part.rule.get())) {
      grid->grow(now, reached, changed);
      continue;
    }
    // First pieces, or a baseline rule: rebuilt whole. A new piece changes
    // only the factors of the nodes it reaches (their view of the cut).
    part.rule = make_rule(part, reached);
    changed.insert(changed.end(), reached.begin(), reached.end());
  }
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  return changed;
}

const EnrichmentGrid* CutWeights::grid(Index cut) const {
  const auto* g = dynamic_cast<const GridRule*>(parts_[cut].rule.get());
  return g ? &g->grid() : nullptr;
}

}  // namespace kerf
