// Enrichment of the MLS weights by a cut: phi is +1 and -1 on the two faces,
// continuous around and ahead of the tips (0 on the extension), its analytic
// gradient matches finite differences away from the cut (single piece, the
// Enrichment Grid of a kinked polyline, a 3D strip); an enriched node's weight
// vanishes across the faces but not around the tips; every rule's weight
// factor has the gradient of its finite differences; enriched MLS still
// reproduces linear fields, to round-off, right next to the cut.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "discretization/enrichment/cut_phi.h"
#include "discretization/enrichment/diffraction_rule.h"
#include "discretization/enrichment/grid_rule.h"
#include "discretization/enrichment/multiplicative_rule.h"
#include "discretization/enrichment/single_piece_rule.h"
#include "discretization/enrichment/visibility_rule.h"
#include "discretization/meshless/mls_shape.h"

namespace kerf {
namespace {

CutSurface straight_2d() { return cut_surface(2, {Vec3(-0.5, 0, 0), Vec3(0.5, 0, 0)}, {0, 0}, ""); }
CutSurface kinked_2d() {
  return cut_surface(2, {Vec3(-0.6, 0, 0), Vec3(-0.1, 0.15, 0), Vec3(0.2, -0.05, 0), Vec3(0.6, 0.1, 0)},
                     {0, 0, 0, 0}, "");
}
CutSurface strip_3d() {
  // A blade edge from y = -0.3 to 0.3 swept along x, tilting a little.
  return cut_surface(3,
                     {Vec3(-0.5, -0.3, 0), Vec3(-0.5, 0.3, 0.02), Vec3(0, -0.3, 0.05), Vec3(0, 0.3, 0.04),
                      Vec3(0.5, -0.3, 0.0), Vec3(0.5, 0.3, 0.03)},
                     std::vector<double>(6, 0.0), "");
}

/// The grid rule for these nodes (exact lookup unless told).
std::unique_ptr<GridRule> grid_rule(const CutSurface& c, Index pieces, const std::vector<Vec3>& nodes,
                                    const std::vector<double>& support, GridLookup lookup = GridLookup::exact,
                                    double spacing = 0.01) {
  const std::vector<char> flags = nodes_reached(c, pieces, nodes, support);
  std::vector<Index> reached;
  for (std::size_t I = 0; I < flags.size(); ++I)
    if (flags[I]) reached.push_back(static_cast<Index>(I));
  return std::make_unique<GridRule>(c, pieces, spacing, lookup, nodes, support, reached);
}

PhiValue whole_phi(const CutSurface& c, const Vec3& x) {
  return grid_phi(c, 0, c.piece_count(), common_frame(c, 0, c.piece_count()), x);
}

TEST(CutPhi, PlusAndMinusOneOnTheFacesZeroAheadOfTheTips) {
  for (const CutSurface& c : {straight_2d(), kinked_2d()}) {
    for (double t : {-0.4, -0.1, 0.0, 0.15, 0.4}) {
      const CutFrame f = common_frame(c, 0, c.piece_count());
      const CutRegion r = cut_region(c, 0, c.piece_count(), f, Vec3(t, 0, 0));
      const Vec3 on = Vec3(t, 0, 0) - r.s * c.pieces[r.piece].normal;  // the point of the cut below x
      EXPECT_DOUBLE_EQ(whole_phi(c, on + 1e-7 * c.pieces[r.piece].normal).value, 1.0);
      EXPECT_DOUBLE_EQ(whole_phi(c, on - 1e-7 * c.pieces[r.piece].normal).value, -1.0);
    }
    // On the cut exactly (its vertices, tips included): the + side.
    for (const Vec3& v : c.vertices) EXPECT_DOUBLE_EQ(whole_phi(c, v).value, 1.0);
  }
  EXPECT_DOUBLE_EQ(whole_phi(straight_2d(), Vec3(0.2, 0, 0)).value, 1.0);
  // Ahead of the tip of the straight cut, on its extension, phi = 0; around
  // the tip it moves smoothly from +1 to -1.
  const CutSurface c = straight_2d();
  EXPECT_DOUBLE_EQ(whole_phi(c, Vec3(0.7, 0, 0)).value, 0.0);
  double previous = 1.0;
  for (int k = 1; k < 64; ++k) {
    const double angle = std::numbers::pi * k / 64.0;  // from above the tip round to below it
    const Vec3 x(0.5 + 0.01 * std::sin(angle), 0.01 * std::cos(angle), 0);
    const double phi = whole_phi(c, x).value;
    EXPECT_LT(phi, previous);
    EXPECT_LT(previous - phi, 0.06);  // no jump around the tip
    previous = phi;
  }
  // 3D: the two faces of the strip (its normal points down: blade along +y, swept along +x).
  const CutSurface s = strip_3d();
  ASSERT_LT(s.pieces[0].normal.z(), 0.0);
  EXPECT_DOUBLE_EQ(whole_phi(s, Vec3(0.1, 0.1, -0.2)).value, 1.0);
  EXPECT_DOUBLE_EQ(whole_phi(s, Vec3(0.1, 0.1, 0.2)).value, -1.0);
  EXPECT_NEAR(whole_phi(s, Vec3(0.1, 0.6, 0.035)).value, 0.0, 0.1);  // beyond the blade's edge, about level
}

TEST(CutPhi, AnalyticGradientMatchesFiniteDifferencesAwayFromTheCut) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double h = 1e-6;
  int checked = 0;
  for (const CutSurface& c : {straight_2d(), kinked_2d(), strip_3d()}) {
    const int dim = c.dimension;
    for (int trial = 0; trial < 200; ++trial) {
      Vec3 x(u(random), u(random), dim == 3 ? u(random) : 0.0);
      if (distance_to_cut(c, 0, c.piece_count(), x) < 0.05) continue;
      const PhiValue p = whole_phi(c, x);
      Vec3 fd = Vec3::Zero();
      bool smooth = true;
      for (int i = 0; i < dim; ++i) {
        Vec3 e = Vec3::Zero();
        e[i] = h;
        const double plus = whole_phi(c, x + e).value, minus = whole_phi(c, x - e).value;
        // Region boundaries beyond the tips (3D) may jump: skip points on them.
        smooth &= std::abs(plus - minus) < 1e-3;
        fd[i] = (plus - minus) / (2 * h);
      }
      if (!smooth) continue;
      EXPECT_LT((fd - p.gradient).norm(), 1e-6 * (1.0 + p.gradient.norm())) << "at " << x.transpose();
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
}

/// The weight factors of every rule: g in [0, 1], its gradient by finite differences.
TEST(EnrichmentRule, FactorsHaveTheGradientsOfTheirFiniteDifferences) {
  const CutSurface c = kinked_2d();
  const std::vector<Vec3> nodes = {Vec3(-0.2, 0.2, 0), Vec3(0.3, -0.2, 0), Vec3(0.55, 0.3, 0), Vec3(0.0, -0.1, 0)};
  const std::vector<double> support(nodes.size(), 0.6);
  const Index n = c.piece_count();
  std::vector<std::unique_ptr<EnrichmentRule>> rules;
  rules.push_back(grid_rule(c, n, nodes, support));
  rules.push_back(std::make_unique<SinglePieceRule>(c, n, nodes, support));
  rules.push_back(std::make_unique<MultiplicativeRule>(c, n, nodes, support));
  rules.push_back(std::make_unique<DiffractionRule>(c, n, nodes, support));
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-0.8, 0.8);
  const double h = 1e-6;
  std::vector<int> checked(rules.size(), 0);
  for (std::size_t r = 0; r < rules.size(); ++r)
    for (Index I = 0; I < static_cast<Index>(nodes.size()); ++I) {
      ASSERT_TRUE(rules[r]->enriches(I));
      for (int trial = 0; trial < 50; ++trial) {
        const Vec3 x(u(random), u(random), 0);
        // Within the front's core grad g is bounded on purpose (FrontCoreBoundsTheGradient).
        const double core = front_core * support[I];
        if (distance_to_cut(c, 0, n, x) < std::max(0.02, core) || (x - nodes[I]).norm() > 0.58) continue;
        const WeightFactor g = rules[r]->factor(I, x);
        EXPECT_GE(g.value, 0.0);
        EXPECT_LE(g.value, 1.0 + 1e-12);
        Vec3 fd = Vec3::Zero();
        bool smooth = true;
        for (int i = 0; i < 2; ++i) {
          Vec3 e = Vec3::Zero();
          e[i] = h;
          const double plus = rules[r]->factor(I, x + e).value, minus = rules[r]->factor(I, x - e).value;
          smooth &= std::abs(plus - minus) < 1e-3;  // diffraction switches on across rays through the tips
          fd[i] = (plus - minus) / (2 * h);
        }
        if (!smooth) continue;
        EXPECT_LT((fd - g.gradient).norm(), 1e-5 * (1.0 + g.gradient.norm())) << "rule " << r << " node " << I;
        ++checked[r];
      }
    }
  // Of the 200 samples per rule, those outside the support, near the cut or
  // across diffraction's rays are skipped: 71-77 per rule are left (measured).
  for (std::size_t r = 0; r < rules.size(); ++r) EXPECT_GE(checked[r], 60) << "rule " << r;
}

TEST(EnrichmentRule, AnEnrichedWeightVanishesAcrossTheFacesNotAroundTheTips) {
  const CutSurface c = straight_2d();
  const std::vector<Vec3> nodes = {Vec3(0.0, 0.05, 0), Vec3(0.45, 0.05, 0), Vec3(0.0, 2.0, 0)};
  const std::vector<double> support = {0.3, 0.3, 0.3};
  const auto grid_owner = grid_rule(c, 1, nodes, support);
  const GridRule& grid = *grid_owner;
  VisibilityRule visibility(c, 1, nodes, support);
  EXPECT_FALSE(grid.enriches(2));  // its support does not reach the cut
  for (const EnrichmentRule* rule : std::initializer_list<const EnrichmentRule*>{&grid, &visibility}) {
    EXPECT_EQ(rule->factor(0, Vec3(0.0, -0.05, 0)).value, 0.0);  // straight across the face
    EXPECT_EQ(rule->factor(0, Vec3(0.1, 0.1, 0)).value, 1.0);    // same side
  }
  // Around the tip the grid's weight fades smoothly: half ahead of the tip,
  // and still seen a little below it.
  EXPECT_NEAR(grid.factor(1, Vec3(0.6, 0.0, 0)).value, 0.5, 1e-12);
  const double below = grid.factor(1, Vec3(0.55, -0.05, 0)).value;
  EXPECT_GT(below, 0.1);
  EXPECT_LT(below, 0.5);
}

// grad phi grows as 1/d at the cut's front: a point the front passes
// through (a node of a mesh on the blade's line) sampled it at 1e16/m and
// the explicit critical step fell to 1e-17 s. Within front_core of the
// support radius the gradient is that at the core's edge scaled by d / core
// (bounded, continuous there), the value stays exact, and outside it nothing
// changes.
TEST(EnrichmentRule, FrontCoreBoundsTheGradient) {
  const CutSurface c = straight_2d();  // front at (0.5, 0)
  const std::vector<Vec3> nodes = {Vec3(0.45, 0.05, 0)};
  const std::vector<double> support = {0.32};
  const double core = front_core * support[0];
  ASSERT_NEAR(core, 0.02, 1e-15);
  std::vector<std::unique_ptr<EnrichmentRule>> rules;
  rules.push_back(grid_rule(c, 1, nodes, support));
  rules.push_back(std::make_unique<SinglePieceRule>(c, 1, nodes, support));
  rules.push_back(std::make_unique<MultiplicativeRule>(c, 1, nodes, support));
  for (std::size_t r = 0; r < rules.size(); ++r) {
    for (double angle : {-2.5, -1.0, 0.3, 1.2, 2.9}) {  // around the front, ahead of it and beside the faces
      const Vec3 direction(std::cos(angle), std::sin(angle), 0);
      const PhiValue outside = whole_phi(c, Vec3(0.5, 0, 0) + 1.5 * core * direction);
      const WeightFactor far = rules[r]->factor(0, Vec3(0.5, 0, 0) + 1.5 * core * direction);
      EXPECT_NEAR((far.gradient - 0.5 * outside.gradient).norm(), 0.0, 1e-12) << "rule " << r;  // untouched
      for (double d : {1e-18, 1e-9, 0.5 * core}) {
        const Vec3 x = Vec3(0.5, 0, 0) + d * direction;
        const PhiValue exact = whole_phi(c, x);
        const WeightFactor g = rules[r]->factor(0, x);
        EXPECT_DOUBLE_EQ(g.value, 0.5 * (1.0 + exact.value)) << "rule " << r;
        EXPECT_LE(g.gradient.norm(), 0.5 / core * (1.0 + 1e-12)) << "rule " << r << " d " << d;
        // Ahead of the front d is the distance to it; behind it |s| (grad phi is 0 there). x rounds to 1e-16.
        if (direction.x() > 0) {
          EXPECT_NEAR(exact.front_distance, d, 1e-12 * d + 1e-16);
        }
        EXPECT_LE(exact.front_distance, d + 1e-16);
        const double scale = exact.front_distance / core;
        EXPECT_NEAR((g.gradient - 0.5 * exact.gradient * scale).norm(), 0.0, 1e-12 / core) << "rule " << r;
      }
    }
  }
  // What the core bounds: a point one ulp ahead of the front.
  EXPECT_GT(whole_phi(c, Vec3(std::nextafter(0.5, 1.0), 1e-16, 0)).gradient.norm(), 1e15);
}

// A node or point lying on the cut belongs to its +1 side (where the normal
// points): the grid's phi there is +1 by its convention, and visibility and
// diffraction take it a hair above, so a node there sees one side only and
// a point there is hidden from the nodes below (seeing both would glue the
// faces together).
TEST(EnrichmentRule, ANodeOnTheCutSeesItsPlusSideOnly) {
  const CutSurface c = straight_2d();  // normal +y
  const std::vector<Vec3> nodes = {Vec3(0.1, 0.0, 0)};
  const std::vector<double> support = {0.3};
  const auto grid = grid_rule(c, 1, nodes, support);
  VisibilityRule visibility(c, 1, nodes, support);
  DiffractionRule diffraction(c, 1, nodes, support);
  for (const EnrichmentRule* rule :
       std::initializer_list<const EnrichmentRule*>{grid.get(), &visibility, &diffraction}) {
    EXPECT_EQ(rule->factor(0, Vec3(0.12, 0.05, 0)).value, 1.0);
    EXPECT_EQ(rule->factor(0, Vec3(0.12, -0.05, 0)).value, 0.0);
  }
  // A point on the cut is seen from the + side, not from below.
  const std::vector<Vec3> below = {Vec3(0.1, -0.05, 0)};
  VisibilityRule from_below(c, 1, below, support);
  DiffractionRule around_below(c, 1, below, support);
  EXPECT_EQ(from_below.factor(0, Vec3(0.12, 0.0, 0)).value, 0.0);
  EXPECT_LT(around_below.factor(0, Vec3(0.12, 0.0, 0)).value, 1e-3);
}

TEST(EnrichmentRule, EnrichedMlsReproducesLinearFieldsNextToTheCut) {
  const CutSurface c = kinked_2d();
  std::vector<Vec3> nodes;
  std::vector<double> support;
  const double h = 0.05;
  for (int i = -20; i <= 20; ++i)
    for (int j = -10; j <= 10; ++j) {
      nodes.emplace_back(i * h + 0.013, j * h + 0.021, 0);
      support.push_back(2.6 * h);
    }
  const auto grid_owner = grid_rule(c, c.piece_count(), nodes, support);
  const GridRule& grid = *grid_owner;
  auto field = [](const Vec3& x) { return 0.3 + 2.0 * x.x() - 1.5 * x.y(); };
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(-0.7, 0.7);
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Vec3 x(u(random), 0.5 * u(random), 0);
    std::vector<Vec3> near;
    std::vector<WeightValue> w;
    for (std::size_t I = 0; I < nodes.size(); ++I) {
      WeightValue wI = quartic_weight(x, nodes[I], support[I]);
      if (wI.value <= 0.0) continue;
      const WeightFactor g = grid.factor(static_cast<Index>(I), x);
      wI.gradient = g.value * wI.gradient + wI.value * g.gradient;
      wI.value *= g.value;
      near.push_back(nodes[I]);
      w.push_back(wI);
    }
    MlsShape shape;
    if (!mls_shape_functions(2, MlsBasis::linear, x, near, w, 2.6 * h, false, shape)) continue;
    double value = 0.0;
    Vec3 gradient = Vec3::Zero();
    for (std::size_t k = 0; k < near.size(); ++k) {
      value += shape.value[k] * field(near[k]);
      gradient += shape.gradient[k] * field(near[k]);
    }
    EXPECT_NEAR(value, field(x), 1e-10);
    EXPECT_NEAR(gradient.x(), 2.0, 1e-8);
    EXPECT_NEAR(gradient.y(), -1.5, 1e-8);
    ++checked;
  }
  EXPECT_GT(checked, 350);
}

}  // namespace
}  // namespace kerf
