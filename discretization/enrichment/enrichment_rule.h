#pragma once
// How cuts enter the MLS shape functions (DESIGN.md): node I's weight becomes
// w_I(x) g_I(x), with g_I in [0, 1] vanishing where x is hidden from node I by
// a cut. Only nodes whose support reaches a cut are enriched (g = 1 for the
// others). One implementation per rule: the Enrichment Grid (GridRule),
// Barbieri's single-piece and multiplicative rules, visibility and
// diffraction; CutWeights combines the rules of all of a scene's cuts.
#include <span>
#include <vector>

#include "core/types.h"
#include "discretization/enrichment/cut_phi.h"
#include "geometry/cut_surface.h"

namespace kerf {

struct WeightFactor {
  double value = 1.0;
  Vec3 gradient = Vec3::Zero();  // 1/m
};

/// (a b) and (a b)' = a' b + a b': how factors combine.
inline WeightFactor operator*(const WeightFactor& a, const WeightFactor& b) {
  return {a.value * b.value, a.gradient * b.value + a.value * b.gradient};
}

/// g = (1 + sigma phi) / 2 for a node on side sigma (+1 or -1) of radius
/// `support` (m). Around the cut's front grad phi ~ 1/d: a point within
/// front_core of the support radius of the front (a node the front passes
/// through, d ~ 1e-18 m) takes grad phi scaled by d / core: bounded, of the
/// order of a small cell's mean, not a 1e16/m sample. The MLS derivatives stay
/// linearly consistent for any weight gradients, so patch tests still pass.
WeightFactor side_factor(const PhiValue& phi, int side, double support);
inline constexpr double front_core = 1.0 / 16.0;

class EnrichmentRule {
 public:
  virtual ~EnrichmentRule() = default;
  /// Does a cut change node I's weight anywhere?
  virtual bool enriches(Index node) const = 0;
  /// g_I(x) and its gradient.
  virtual WeightFactor factor(Index node, const Vec3& x) const = 0;
  /// The factors of several nodes at one point (out[k] for nodes[k]; 1 for a
  /// node not enriched), as factor() gives them: rules whose g depends on x
  /// through one field for all nodes (the grid's phi) look it up once.
  virtual void factors(std::span<const Index> nodes, const Vec3& x, std::span<WeightFactor> out) const;
};

/// The nodes a cut's first `pieces` pieces reach: distance to the cut below the support radius.
std::vector<char> nodes_reached(const CutSurface& cut, Index pieces, std::span<const Vec3> nodes,
                                std::span<const double> support);

}  // namespace kerf
