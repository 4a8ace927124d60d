#include "discretization/enrichment/diffraction_rule.h"

#include <limits>

#include "discretization/meshless/mls_shape.h"

namespace kerf {

DiffractionRule::DiffractionRule(const CutSurface& cut, Index pieces, std::span<const Vec3> nodes,
                                 std::span<const double> support)
    : cut_(cut),
      pieces_(pieces),
      nodes_(nodes.begin(), nodes.end()),
      viewpoints_(nodes.begin(), nodes.end()),
      support_(support.begin(), support.end()) {
  enriched_ = nodes_reached(cut_, pieces_, nodes, support);
  for (std::size_t I = 0; I < viewpoints_.size(); ++I)
    if (enriched_[I]) viewpoints_[I] = off_the_cut(cut_, pieces_, viewpoints_[I]);
  const auto& v = cut_.vertices;
  if (cut_.dimension == 2) {
    edges_ = {{v[0], v[0]}, {v[pieces_], v[pieces_]}};
    return;
  }
  // A strip's boundary: its first and last cross edges and its two long sides.
  edges_.push_back({v[0], v[1]});
  for (Index k = 0; k < pieces_; ++k) edges_.push_back({v[k], v[k + 2]});
  edges_.push_back({v[pieces_], v[pieces_ + 1]});
}

Vec3 DiffractionRule::bend_point(const Vec3& a, const Vec3& b) const {
  Vec3 best = edges_.front()[0];
  double best_length = std::numeric_limits<double>::infinity();
  for (const auto& e : edges_) {
    // |a - c| + |c - b| is convex along the edge: ternary search.
    auto length = [&](double u) {
      const Vec3 c = e[0] + u * (e[1] - e[0]);
      return (a - c).norm() + (c - b).norm();
    };
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 60 && (e[1] - e[0]).squaredNorm() > 0.0; ++i) {
      const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
      if (length(m1) < length(m2))
        hi = m2;
      else
        lo = m1;
    }
    const double u = 0.5 * (lo + hi);
    if (length(u) < best_length) best_length = length(u), best = e[0] + u * (e[1] - e[0]);
  }
  return best;
}

WeightFactor DiffractionRule::factor(Index node, const Vec3& x) const {
  if (!enriched_[node]) return {};
  const Vec3& a = viewpoints_[node];
  if (!segment_crosses_cut(cut_, 0, pieces_, a, off_the_cut(cut_, pieces_, x))) return {};
  const WeightValue straight = quartic_weight(x, nodes_[node], support_[node]);
  if (straight.value <= 0.0) return {0.0, Vec3::Zero()};
  const Vec3 c = bend_point(a, x);
  const double rest = (x - c).norm(), d = (a - c).norm() + rest;
  // The quartic at distance d, and its derivative along the last leg (c held fixed).
  const WeightValue bent = quartic_weight(Vec3(d, 0.0, 0.0), Vec3::Zero(), support_[node]);
  const Vec3 direction = rest > 0.0 ? Vec3((x - c) / rest) : Vec3::Zero();
  const Vec3 bent_gradient = bent.gradient.x() * direction;
  WeightFactor g;
  g.value = bent.value / straight.value;
  g.gradient = (bent_gradient - g.value * straight.gradient) / straight.value;
  return g;
}

}  // namespace kerf
