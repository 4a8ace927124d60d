#include "discretization/enrichment/weight_enrichment.h"

#include "core/check.h"
#include "discretization/enrichment/diffraction_enrichment.h"
#include "discretization/enrichment/multiplicative_enrichment.h"
#include "discretization/enrichment/phi_field_enrichment.h"
#include "discretization/enrichment/visibility_enrichment.h"

namespace kerf {
namespace {

/// Several cuts: their factors multiply.
class CombinedEnrichment final : public WeightEnrichment {
 public:
  explicit CombinedEnrichment(std::vector<std::unique_ptr<WeightEnrichment>> parts) : parts_(std::move(parts)) {}
  bool enriches(Index node) const override {
    for (const auto& p : parts_)
      if (p->enriches(node)) return true;
    return false;
  }
  WeightFactor factor(Index node, const Vec3& x) const override {
    WeightFactor g;
    for (const auto& p : parts_) g = g * p->factor(node, x);
    return g;
  }

 private:
  std::vector<std::unique_ptr<WeightEnrichment>> parts_;
};

std::unique_ptr<WeightEnrichment> one_cut(const Cut& cut, const CutSurface& surface, Index pieces,
                                          std::span<const Vec3> nodes, std::span<const double> support) {
  switch (cut.enrichment) {
    case Enrichment::grid:
      KERF_CHECK(cut.grid_lookup == GridLookup::exact, cut.where.describe(),
                 ": key 'grid.lookup': value 'interpolated' is not built yet; expected 'exact'");
      return std::make_unique<PhiFieldEnrichment>(surface, pieces, PhiFieldEnrichment::Field::grid, nodes, support);
    case Enrichment::single:
      return std::make_unique<PhiFieldEnrichment>(surface, pieces, PhiFieldEnrichment::Field::nearest_piece, nodes,
                                                  support);
    case Enrichment::multiplicative:
      return std::make_unique<MultiplicativeEnrichment>(surface, pieces, nodes, support);
    case Enrichment::visibility:
      return std::make_unique<VisibilityEnrichment>(surface, pieces, nodes, support);
    case Enrichment::diffraction:
      return std::make_unique<DiffractionEnrichment>(surface, pieces, nodes, support);
  }
  return nullptr;
}

}  // namespace

std::vector<char> nodes_reached(const CutSurface& cut, Index pieces, std::span<const Vec3> nodes,
                                std::span<const double> support) {
  std::vector<char> reached(nodes.size(), 0);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t I = 0; I < nodes.size(); ++I)
    reached[I] = distance_to_cut(cut, 0, pieces, nodes[I]) < support[I];
  return reached;
}

std::unique_ptr<WeightEnrichment> make_weight_enrichment(std::span<const Cut> cuts,
                                                         std::span<const CutSurface> surfaces,
                                                         std::span<const Vec3> nodes,
                                                         std::span<const double> support, double time) {
  KERF_CHECK(cuts.size() == surfaces.size(), "one surface per cut expected");
  std::vector<std::unique_ptr<WeightEnrichment>> parts;
  for (std::size_t c = 0; c < cuts.size(); ++c) {
    const Index pieces = surfaces[c].pieces_at(time);
    if (pieces > 0) parts.push_back(one_cut(cuts[c], surfaces[c], pieces, nodes, support));
  }
  if (parts.empty()) return nullptr;
  if (parts.size() == 1) return std::move(parts.front());
  return std::make_unique<CombinedEnrichment>(std::move(parts));
}

}  // namespace kerf
