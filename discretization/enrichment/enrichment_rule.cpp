#include "discretization/enrichment/enrichment_rule.h"

#include "core/parallel_failure.h"

namespace kerf {

void EnrichmentRule::factors(std::span<const Index> nodes, const Vec3& x, std::span<WeightFactor> out) const {
  for (std::size_t k = 0; k < nodes.size(); ++k) out[k] = enriches(nodes[k]) ? factor(nodes[k], x) : WeightFactor{};
}

WeightFactor side_factor(const PhiValue& phi, int side, double support) {
  const double core = front_core * support, scale = phi.front_distance < core ? phi.front_distance / core : 1.0;
  return {0.5 * (1.0 + side * phi.value), 0.5 * side * scale * phi.gradient};
}

std::vector<char> nodes_reached(const CutSurface& cut, Index pieces, std::span<const Vec3> nodes,
                                std::span<const double> support) {
  std::vector<char> reached(nodes.size(), 0);
  ParallelFailure failure;
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t I = 0; I < nodes.size(); ++I)
    failure.run([&] { reached[I] = distance_to_cut(cut, 0, pieces, nodes[I]) < support[I]; });
  failure.rethrow_if_failed();
  return reached;
}

}  // namespace kerf
