#pragma once
// Every cut of a scene entering the MLS weights as time goes on: each cut's
// rule (the scene's `enrichment`), their factors multiplied.
#include <memory>
#include <span>
#include <vector>

#include "discretization/cut_timeline.h"
#include "discretization/enrichment/enrichment_rule.h"
#include "geometry/support_index.h"

namespace kerf {

class EnrichmentGrid;

/// Every cut of a scene at the current time; their factors multiply
/// (separate cuts are separate surfaces). A piece joins its cut at the time
/// of its last vertex; advance_to() brings the cuts to a later time and tells
/// which nodes' factors changed. The grid rule updates incrementally; the
/// other rules (baselines) are rebuilt and report the nodes the new pieces reach.
class CutWeights final : public EnrichmentRule {
 public:
  /// The scene's cuts (kept); `index` holds the nodes and their support radii
  /// (m) and must outlive this object.
  CutWeights(SharedCuts cuts, const SupportIndex& index, double time);
  ~CutWeights() override;

  /// Is any piece of any cut present?
  bool present() const;
  bool enriches(Index node) const override;
  WeightFactor factor(Index node, const Vec3& x) const override;
  /// Each cut's rule asked once for all the nodes, their factors multiplied as factor() does.
  void factors(std::span<const Index> nodes, const Vec3& x, std::span<WeightFactor> out) const override;

  /// Brings the cuts to time t (never earlier than before); returns the nodes
  /// whose g_I changed, sorted and unique (empty when no piece appeared).
  std::vector<Index> advance_to(double t);
  /// May the last advance_to that changed something have changed the factors
  /// at x of the nodes `near`? False when none of them changed over its whole
  /// support (newly enriched, side turned, a rebuilt rule's) and every grown
  /// grid kept phi at x: the shape functions there stay as they were.
  bool growth_may_change(const Vec3& x, std::span<const Index> near) const;

  /// The Enrichment Grid of cut c (null for other rules or before its first piece).
  const EnrichmentGrid* grid(Index cut) const;
  /// Pieces of cut c present now.
  Index pieces(Index cut) const { return parts_[cut].pieces; }
  Index cut_count() const { return static_cast<Index>(parts_.size()); }
  const CutSurface& surface(Index cut) const { return cuts_->surface(cut); }

 private:
  struct Part {
    Index pieces = 0;  // present now
    std::unique_ptr<EnrichmentRule> rule;
  };
  /// The nodes whose support reaches pieces [first, last) of a surface, sorted.
  std::vector<Index> reached_by(const CutSurface& surface, Index first, Index last) const;
  std::unique_ptr<EnrichmentRule> make_rule(Index cut, std::span<const Index> reached) const;
  /// Keeps what growth_may_change asks about the growth advance_to just made.
  void remember_growth(std::vector<Index> everywhere, std::vector<Index> grown);

  SharedCuts cuts_;
  std::vector<Part> parts_;  // one per cut
  // The last growth: the nodes whose factor changed over their whole support
  // (flags and list), and the cuts whose grid grew (their phi changed near their columns).
  std::vector<char> changed_everywhere_;
  std::vector<Index> changed_everywhere_list_;
  std::vector<Index> grown_grids_;
  const SupportIndex& index_;
  const std::vector<Vec3>& nodes_;      // index_'s
  const std::vector<double>& support_;  // index_'s
};

}  // namespace kerf
