#include "discretization/enrichment/weight_enrichment.h"

#include <algorithm>

#include "core/check.h"
#include "discretization/enrichment/diffraction_enrichment.h"
#include "discretization/enrichment/grid_enrichment.h"
#include "discretization/enrichment/multiplicative_enrichment.h"
#include "discretization/enrichment/single_piece_enrichment.h"
#include "discretization/enrichment/visibility_enrichment.h"

namespace kerf {

std::vector<char> nodes_reached(const CutSurface& cut, Index pieces, std::span<const Vec3> nodes,
                                std::span<const double> support) {
  std::vector<char> reached(nodes.size(), 0);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t I = 0; I < nodes.size(); ++I)
    reached[I] = distance_to_cut(cut, 0, pieces, nodes[I]) < support[I];
  return reached;
}

CutEnrichment::CutEnrichment(std::span<const Cut> cuts, std::vector<CutSurface> surfaces,
                             std::span<const Vec3> nodes, std::span<const double> support, const PointIndex& index,
                             double time)
    : nodes_(nodes.begin(), nodes.end()), support_(support.begin(), support.end()), index_(index) {
  KERF_CHECK(cuts.size() == surfaces.size(), "one surface per cut expected");
  if (!support.empty()) largest_support_ = *std::max_element(support.begin(), support.end());
  for (std::size_t c = 0; c < cuts.size(); ++c) parts_.push_back(Part{cuts[c], std::move(surfaces[c]), 0, nullptr});
  advance_to(time);
}

CutEnrichment::~CutEnrichment() = default;

bool CutEnrichment::present() const {
  return std::any_of(parts_.begin(), parts_.end(), [](const Part& p) { return p.pieces > 0; });
}

bool CutEnrichment::enriches(Index node) const {
  for (const Part& p : parts_)
    if (p.rule && p.rule->enriches(node)) return true;
  return false;
}

WeightFactor CutEnrichment::factor(Index node, const Vec3& x) const {
  WeightFactor g;
  for (const Part& p : parts_)
    if (p.rule && p.rule->enriches(node)) g = g * p.rule->factor(node, x);
  return g;
}

std::vector<Index> CutEnrichment::reached_by(const CutSurface& surface, Index first, Index last) const {
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

std::unique_ptr<WeightEnrichment> CutEnrichment::make_rule(const Part& part, std::span<const Index> reached) const {
  const CutSurface& s = part.surface;
  switch (part.cut.enrichment) {
    case Enrichment::grid:
      return std::make_unique<GridEnrichment>(s, part.pieces, part.cut.grid_spacing, part.cut.grid_lookup, nodes_,
                                              support_, reached);
    case Enrichment::single:
      return std::make_unique<SinglePieceEnrichment>(s, part.pieces, nodes_, support_);
    case Enrichment::multiplicative:
      return std::make_unique<MultiplicativeEnrichment>(s, part.pieces, nodes_, support_);
    case Enrichment::visibility:
      return std::make_unique<VisibilityEnrichment>(s, part.pieces, nodes_, support_);
    case Enrichment::diffraction:
      return std::make_unique<DiffractionEnrichment>(s, part.pieces, nodes_, support_);
  }
  return nullptr;
}

std::vector<Index> CutEnrichment::advance_to(double t) {
  std::vector<Index> changed;
  for (Part& part : parts_) {
    const Index now = part.surface.pieces_at(t);
    if (now <= part.pieces) continue;
    const Index before = part.pieces;
    part.pieces = now;
    const std::vector<Index> reached = reached_by(part.surface, before, now);
    if (auto* grid = dynamic_cast<GridEnrichment*>(part.rule.get())) {
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

const EnrichmentGrid* CutEnrichment::grid(Index cut) const {
  const auto* g = dynamic_cast<const GridEnrichment*>(parts_[cut].rule.get());
  return g ? &g->grid() : nullptr;
}

}  // namespace kerf
