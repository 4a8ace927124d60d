#include "discretization/enrichment/grid_rule.h"

#include <algorithm>
#include <optional>

#include "core/parallel_failure.h"

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
  side_[node] = node_side(node);
}

signed char GridRule::node_side(Index node) const {
  // From the exact phi: a node's side must not depend on the lookup.
  return grid_->exact(nodes_[node]).value >= 0.0 ? 1 : -1;
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
                    std::vector<Index>& changed, std::vector<Index>* everywhere) {
  // Assigned in place: the grids point at this object, and the pieces they
  // were built from stay the same at the front of the new copy.
  if (cut.piece_count() != cut_.piece_count()) cut_ = cut;
  std::unique_ptr<EnrichmentGrid> before = std::move(grid_);
  grid_ = std::make_unique<EnrichmentGrid>(cut_, pieces, spacing_, padding_, *before);
  // Interpolating on a lattice that turned with the cut changes phi near the
  // faces everywhere: then every enriched node is updated.
  lattice_moved_ = lookup_ == GridLookup::interpolated && !grid_->same_lattice(*before);
  // Which enriched nodes the grown columns reach, and their side now (the
  // exact phi at each): in parallel, then taken in list order.
  const Index count = static_cast<Index>(enriched_list_.size());
  std::vector<signed char> side(count, 0);  // 0: not reached
  ParallelFailure failure;
#pragma omp parallel for schedule(dynamic, 64)
  for (Index k = 0; k < count; ++k)
    failure.run([&] {
      const Index I = enriched_list_[k];
      if (lattice_moved_ || grid_->reaches_changed_column(nodes_[I], support_[I])) side[k] = node_side(I);
    });
  failure.rethrow_if_failed();
  for (Index k = 0; k < count; ++k) {
    if (!side[k]) continue;
    const Index I = enriched_list_[k];
    changed.push_back(I);
    if (everywhere && side[k] != side_[I]) everywhere->push_back(I);
    side_[I] = side[k];
  }
  for (Index I : reached)
    if (!enriched_[I]) {
      enrich(I);
      changed.push_back(I);
      if (everywhere) everywhere->push_back(I);
    }
}

bool GridRule::phi_may_have_changed(const Vec3& x) const {
  // The interpolated lookup reads the four columns around x's projection,
  // all within sqrt(2) spacings of it; the exact one, the cut at the
  // projection itself, whose change the columns' one-column dilation holds.
  constexpr double reach = 1.5;
  return lattice_moved_ || !grid_->knows_changes() || grid_->reaches_changed_column(x, reach * spacing_);
}

}  // namespace kerf
