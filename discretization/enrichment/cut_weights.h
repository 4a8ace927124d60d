#pragma once
// Every cut of a scene entering the MLS weights as time goes on: each cut's
// rule (the scene's `enrichment`), their factors multiplied.
#include <memory>
#include <span>
#include <vector>

#include "discretization/enrichment/enrichment_rule.h"
#include "geometry/neighbor_search.h"
#include "problem/scene.h"

namespace kerf {

class EnrichmentGrid;

/// Every cut of a scene at the current time; their factors multiply
/// (separate cuts are separate surfaces). A piece joins its cut at the time
/// of its last vertex; advance_to() brings the cuts to a later time and tells
/// which nodes' factors changed. The grid rule updates incrementally; the
/// other rules (baselines) are rebuilt and report the nodes the new pieces reach.
class CutWeights final : public EnrichmentRule {
 public:
  /// `cuts` and `surfaces` are parallel (the surfaces are kept here); nodes and support radii in metres;
  /// `index` is a k-d tree over the nodes and must outlive this object.
  CutWeights(std::span<const Cut> cuts, std::vector<CutSurface> surfaces, std::span<const Vec3> nodes,
             std::span<const double> support, const PointIndex& index, double time);
  ~CutWeights() override;

  /// Is any piece of any cut present?
  bool present() const;
  bool enriches(Index node) const override;
  WeightFactor factor(Index node, const Vec3& x) const override;

  /// Brings the cuts to time t (never earlier than before); returns the nodes
  /// whose g_I changed, sorted and unique (empty when no piece appeared).
  std::vector<Index> advance_to(double t);

  /// The Enrichment Grid of cut c (null for other rules or before its first piece).
  const EnrichmentGrid* grid(Index cut) const;
  /// Pieces of cut c present now.
  Index pieces(Index cut) const { return parts_[cut].pieces; }
  Index cut_count() const { return static_cast<Index>(parts_.size()); }
  const CutSurface& surface(Index cut) const { return parts_[cut].surface; }

 private:
  struct Part {
    Cut cut;
    CutSurface surface;
    Index pieces = 0;
    std::unique_ptr<EnrichmentRule> rule;
  };
  /// The nodes whose support reaches pieces [first, last) of a surface, sorted.
  std::vector<Index> reached_by(const CutSurface& surface, Index first, Index last) const;
  std::unique_ptr<EnrichmentRule> make_rule(const Part& part, std::span<const Index> reached) const;

  std::vector<Part> parts_;
  std::vector<Vec3> nodes_;
  std::vector<double> support_;
  double largest_support_ = 0.0;
  const PointIndex& index_;
};

}  // namespace kerf
