#pragma once
// How cuts enter the MLS shape functions (DESIGN.md): node I's weight becomes
// w_I(x) g_I(x), with g_I in [0, 1] vanishing where x is hidden from node I by
// a cut. Only nodes whose support reaches a cut are enriched (g = 1 for the
// others). One implementation per rule: the Enrichment Grid, Barbieri's
// single-piece and multiplicative rules, visibility and diffraction.
#include <memory>
#include <span>
#include <vector>

#include "core/types.h"
#include "geometry/cut_surface.h"
#include "problem/scene.h"

namespace kerf {

struct WeightFactor {
  double value = 1.0;
  Vec3 gradient = Vec3::Zero();  // 1/m
};

/// (a b) and (a b)' = a' b + a b': how factors combine.
inline WeightFactor operator*(const WeightFactor& a, const WeightFactor& b) {
  return {a.value * b.value, a.gradient * b.value + a.value * b.gradient};
}

class WeightEnrichment {
 public:
  virtual ~WeightEnrichment() = default;
  /// Does a cut change node I's weight anywhere?
  virtual bool enriches(Index node) const = 0;
  /// g_I(x) and its gradient.
  virtual WeightFactor factor(Index node, const Vec3& x) const = 0;
};

/// The nodes a cut's first `pieces` pieces reach: distance to the cut below the support radius.
std::vector<char> nodes_reached(const CutSurface& cut, Index pieces, std::span<const Vec3> nodes,
                                std::span<const double> support);

/// The enrichment of every cut present at time t (their factors multiply:
/// separate cuts are separate surfaces); null when no cut is present yet.
/// `cuts` and `surfaces` are parallel; nodes and support radii in metres.
std::unique_ptr<WeightEnrichment> make_weight_enrichment(std::span<const Cut> cuts,
                                                         std::span<const CutSurface> surfaces,
                                                         std::span<const Vec3> nodes,
                                                         std::span<const double> support, double time);

}  // namespace kerf
