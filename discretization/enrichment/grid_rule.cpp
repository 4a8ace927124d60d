#include "discretization/enrichment/grid_rule.h"

#include <algorithm>
#include <optional>

namespace kerf {

GridRule::GridRule(const CutSurface& cut, Index pieces, double spacing, GridLookup lookup, std::span<const Vec3> nodes,
                   std::span<const double> support, std::span<const Index> reached)
    : cut_(cut),
      spacing_(spacing),
      padding_(2.0 * (support.empty() ? 0.0 : *std::max_element(support.begin(), support.end()))),
      lookup_(lookup),
      nodes_(nodes),
      support_(support),
      enriched_(nodes.size(), 0),
      side_(nodes.size(), 1) {
  grid_ = std::make_unique<EnrichmentGrid>(cut_, pieces, spacing_, padding_);
  for (Index I : reached) enrich(I);
}

PhiValue GridRule::phi(const Vec3& x) const {
  return lookup_ == GridLookup::exact ? grid_->exact(x) : grid_->interpolated(x);
}

void GridRule::enrich(Index node) {
  if (!enriched_[node]) enriched_list_.push_back(node);
  enriched_[node] = 1;
  // The side from the exact phi: a node's side must not depend on the lookup.
  side_[node] = grid_->exact(nodes_[node]).value >= 0.0 ? 1 : -1;
}

WeightFactor GridRule::factor(Index node, const Vec3& x) const {
  if (!enriched_[node]) return {};
  return side_factor(phi(x), side_[node], support_[node]);
}

void GridRule::factors(std::span<const Index> nodes, const Vec3& x, std::span<WeightFactor> out) const {
  std::optional<PhiValue> p;  // looked up at the first enriched node
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const Index node = nodes[k];
    if (!enriched_[node]) {
      out[k] = {};
      continue;
    }
    if (!p) p = phi(x);
    out[k] = side_factor(*p, side_[node], support_[node]);
  }
}

void GridRule::grow(const CutSurface& cut, Index pieces, std::span<const Index> reached,
                    std::vector<Index>& changed) {
  // Assigned in place: the grids point at this object, and the pieces they
  // were built from stay the same at the front of the new copy.
  if (cut.piece_count() != cut_.piece_count()) cut_ = cut;
  std::unique_ptr<EnrichmentGrid> before = std::move(grid_);
  grid_ = std::make_unique<EnrichmentGrid>(cut_, pieces, spacing_, padding_, *before);
  const std::vector<char> columns = grid_->changed_columns(*before);
  // Interpolating on a lattice that turned with the cut changes phi near the
  // faces everywhere: then every enriched node is updated.
  const bool moved = lookup_ == GridLookup::interpolated && !grid_->same_lattice(*before);
  for (Index I : enriched_list_)
    if (moved || grid_->reaches(columns, nodes_[I], support_[I])) {
      enrich(I);
      changed.push_back(I);
    }
  for (Index I : reached)
    if (!enriched_[I]) {
      enrich(I);
      changed.push_back(I);
    }
}

}  // namespace kerf
