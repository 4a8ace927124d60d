#include "discretization/enrichment/cut_weights.h"

#include <algorithm>

#include "core/check.h"
#include "discretization/enrichment/diffraction_rule.h"
#include "discretization/enrichment/grid_rule.h"
#include "discretization/enrichment/multiplicative_rule.h"
#include "discretization/enrichment/single_piece_rule.h"
#include "discretization/enrichment/visibility_rule.h"

namespace kerf {

CutWeights::CutWeights(SharedCuts cuts, const SupportIndex& index, double time)
    : cuts_(std::move(cuts)),
      parts_(cuts_->cut_count()),
      index_(index),
      nodes_(index.positions()),
      support_(index.radius()) {
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

void CutWeights::factors(std::span<const Index> nodes, const Vec3& x, std::span<WeightFactor> out) const {
  // The first cut's factors go straight into `out` (one cut, the common case,
  // allocates nothing); each further cut's multiply in (1 where not enriched).
  bool first = true;
  std::vector<WeightFactor> part_factors;
  for (const Part& p : parts_) {
    if (!p.rule) continue;
    if (first) {
      p.rule->factors(nodes, x, out);
      first = false;
      continue;
    }
    part_factors.resize(nodes.size());
    p.rule->factors(nodes, x, part_factors);
    for (std::size_t k = 0; k < nodes.size(); ++k) out[k] = out[k] * part_factors[k];
  }
  if (first) std::fill(out.begin(), out.end(), WeightFactor{});
}

std::vector<Index> CutWeights::reached_by(const CutSurface& surface, Index first, Index last) const {
  std::vector<Index> out, candidates;
  for (Index k = first; k < last; ++k) {
    const CutPiece& piece = surface.pieces[k];
    double radius = 0.0;
    for (int c = 0; c < surface.dimension; ++c) radius = std::max(radius, (piece.corner[c] - piece.centre).norm());
    index_.reaching(piece.centre, radius, candidates, false);  // sorted below
    for (Index I : candidates) {
      // No nearer the piece than its plane (line): most of a large piece's candidates stop here.
      if (std::abs(piece.normal.dot(nodes_[I] - piece.corner[0])) >= support_[I]) continue;
      if (distance_to_cut(surface, k, k + 1, nodes_[I]) < support_[I]) out.push_back(I);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::unique_ptr<EnrichmentRule> CutWeights::make_rule(Index cut, std::span<const Index> reached) const {
  const CutSurface& s = cuts_->surface(cut);
  const Cut& how = cuts_->settings(cut);
  const Index pieces = parts_[cut].pieces;
  switch (how.enrichment) {
    case Enrichment::grid:
      return std::make_unique<GridRule>(s, pieces, how.grid_spacing, how.grid_lookup, nodes_, support_, reached);
    case Enrichment::single:
      return std::make_unique<SinglePieceRule>(s, pieces, nodes_, support_);
    case Enrichment::multiplicative:
      return std::make_unique<MultiplicativeRule>(s, pieces, nodes_, support_);
    case Enrichment::visibility:
      return std::make_unique<VisibilityRule>(s, pieces, nodes_, support_);
    case Enrichment::diffraction:
      return std::make_unique<DiffractionRule>(s, pieces, nodes_, support_);
  }
  return nullptr;
}

std::vector<Index> CutWeights::advance_to(double t) {
  std::vector<Index> changed, everywhere;
  std::vector<Index> grown;
  for (Index c = 0; c < cut_count(); ++c) {
    Part& part = parts_[c];
    const CutSurface& surface = cuts_->surface(c);
    const Index now = surface.pieces_at(t);
    if (now <= part.pieces) continue;
    const Index before = part.pieces;
    part.pieces = now;
    const std::vector<Index> reached = reached_by(surface, before, now);
    if (auto* grid = dynamic_cast<GridRule*>(part.rule.get())) {
      grid->grow(surface, now, reached, changed, &everywhere);
      grown.push_back(c);
      continue;
    }
    // First pieces, or a baseline rule: rebuilt whole. A new piece changes
    // only the factors of the nodes it reaches (their view of the cut).
    part.rule = make_rule(c, reached);
    changed.insert(changed.end(), reached.begin(), reached.end());
    everywhere.insert(everywhere.end(), reached.begin(), reached.end());
  }
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  if (!changed.empty()) remember_growth(std::move(everywhere), std::move(grown));
  return changed;
}

void CutWeights::remember_growth(std::vector<Index> everywhere, std::vector<Index> grown) {
  if (changed_everywhere_.empty()) changed_everywhere_.assign(nodes_.size(), 0);
  for (Index I : changed_everywhere_list_) changed_everywhere_[I] = 0;
  for (Index I : everywhere) changed_everywhere_[I] = 1;
  changed_everywhere_list_ = std::move(everywhere);
  grown_grids_ = std::move(grown);
}

bool CutWeights::growth_may_change(const Vec3& x, std::span<const Index> near) const {
  if (changed_everywhere_.empty()) return true;  // no growth yet
  for (Index I : near)
    if (changed_everywhere_[I]) return true;
  for (Index c : grown_grids_) {
    const auto& rule = static_cast<const GridRule&>(*parts_[c].rule);
    if (std::any_of(near.begin(), near.end(), [&](Index I) { return rule.enriches(I); }) &&
        rule.phi_may_have_changed(x))
      return true;
  }
  return false;
}

const EnrichmentGrid* CutWeights::grid(Index cut) const {
  const auto* g = dynamic_cast<const GridRule*>(parts_[cut].rule.get());
  return g ? &g->grid() : nullptr;
}

}  // namespace kerf
