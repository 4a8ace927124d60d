#pragma once
// The Enrichment Grid's rule (rule `grid`): every enriched node sees the one
// phi of the whole cut, g_I(x) = (1 + sigma_I phi(x)) / 2, sigma_I = +1 or -1
// the side of node I (phi(x_I) >= 0 is the + side), phi served by the grid
// exactly or interpolated. When the cut grows, the grid is rebuilt in the new
// common frame and only the nodes whose support reaches a changed column are
// reported as changed.
#include <memory>

#include "discretization/enrichment/enrichment_grid.h"
#include "discretization/enrichment/enrichment_rule.h"
#include "problem/scene.h"

namespace kerf {

class GridRule final : public EnrichmentRule {
 public:
  /// The cut's first `pieces` pieces (> 0); `reached`: the nodes whose support
  /// reaches them. `nodes` and `support` are viewed, not copied: they must outlive this. Lattice spacing in m; the
  /// lattice reaches twice the largest support radius beyond the cut (as far as a covered point can be).
  GridRule(const CutSurface& cut, Index pieces, double spacing, GridLookup lookup, std::span<const Vec3> nodes,
           std::span<const double> support, std::span<const Index> reached);
  GridRule(const GridRule&) = delete;
  GridRule& operator=(const GridRule&) = delete;

  bool enriches(Index node) const override { return enriched_[node]; }
  WeightFactor factor(Index node, const Vec3& x) const override;
  /// phi(x) once for all the enriched nodes among `nodes`.
  void factors(std::span<const Index> nodes, const Vec3& x, std::span<WeightFactor> out) const override;

  /// The cut grew to `pieces` pieces; `reached`: the nodes whose support
  /// reaches one of the new ones. Appends to `changed` the nodes whose g_I
  /// changed: the newly enriched, and the enriched whose support reaches a
  /// lattice column where phi changed (with interpolation, every enriched
  /// node when the cut turned and the lattice with it).
  /// `cut`: the cut as it stands now, which may hold pieces this rule's copy
  /// lacks (a cut fed at run time); its earlier pieces are this rule's.
  /// `everywhere` (when given) gets the changed nodes whose g_I changed over
  /// their whole support: the newly enriched, and those whose side turned.
  void grow(const CutSurface& cut, Index pieces, std::span<const Index> reached, std::vector<Index>& changed,
            std::vector<Index>* everywhere = nullptr);
  /// Since the last grow, may phi have changed at x (then so did the factor
  /// at x of every node enriched before)? False where every lattice column
  /// the lookup at x reads kept its phi.
  bool phi_may_have_changed(const Vec3& x) const;

  const EnrichmentGrid& grid() const { return *grid_; }
  Index enriched_count() const { return static_cast<Index>(enriched_list_.size()); }

 private:
  PhiValue phi(const Vec3& x) const;
  void enrich(Index node);
  /// sigma_I from the grid as it stands.
  signed char node_side(Index node) const;

  CutSurface cut_;  // the grid points into it: this object does not move
  double spacing_, padding_;
  GridLookup lookup_;
  std::unique_ptr<EnrichmentGrid> grid_;
  std::span<const Vec3> nodes_;
  std::span<const double> support_;
  std::vector<char> enriched_;
  std::vector<Index> enriched_list_;
  std::vector<signed char> side_;  // sigma_I
  bool lattice_moved_ = false;  // the last grow turned an interpolated lattice: phi changed everywhere
};

}  // namespace kerf
