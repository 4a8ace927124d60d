// The Enrichment Grid as a data structure: its interpolated phi converges to
// the exact one away from the faces and keeps the jump across them sharp; a growing cut reports every node whose
// weight factor changed (each node it does not report keeps its factor, to
// round-off, at points all over its support), every point where a factor
// changed is one the growth says phi may have changed at (or the node's
// whole support changed), and after any number of
// growths the factors equal those of a grid built with the whole cut at once.
#include <gtest/gtest.h>

#include <random>

#include "core/check.h"
#include "discretization/enrichment/enrichment_grid.h"
#include "discretization/enrichment/grid_rule.h"
#include "geometry/neighbor_search.h"

namespace kerf {
namespace {

/// A kinked polyline growing a segment at a time (a piece per time 0, 1, 2, ...).
CutSurface growing_polyline() {
  return cut_surface(2,
                     {Vec3(-0.62, 0.013, 0), Vec3(-0.4, 0.013, 0), Vec3(-0.2, 0.08, 0), Vec3(0.0, 0.03, 0),
                      Vec3(0.17, -0.06, 0), Vec3(0.35, -0.02, 0)},
                     {0, 0, 1, 2, 3, 4}, "growing polyline");
}

/// A blade edge from y = -0.3 to 0.3 swept along x in steps, tilting a little.
CutSurface growing_strip() {
  std::vector<Vec3> v;
  std::vector<double> t;
  for (int k = 0; k < 5; ++k) {
    const double x = -0.52 + 0.2 * k, z = 0.013 + 0.02 * std::sin(1.3 * k);
    v.emplace_back(x, -0.3, z), v.emplace_back(x, 0.3, z + 0.01);
    t.push_back(std::max(0, 2 * k - 2)), t.push_back(std::max(0, 2 * k - 1));
  }
  return cut_surface(3, v, t, "growing strip");
}

struct Cloud {
  std::vector<Vec3> nodes;
  std::vector<double> support;
};

Cloud cloud(int dim, double h) {
  Cloud c;
  const int n = static_cast<int>(std::round(0.8 / h));
  for (int k = dim == 3 ? -n / 2 : 0; k <= (dim == 3 ? n / 2 : 0); ++k)
    for (int j = -n / 2; j <= n / 2; ++j)
      for (int i = -n; i <= n; ++i) {
        c.nodes.emplace_back(i * h + 0.0031, j * h + 0.0047, dim == 3 ? k * h + 0.0023 : 0.0);
        c.support.push_back(2.4 * h);
      }
  return c;
}

std::vector<Index> reached(const CutSurface& cut, Index pieces, const Cloud& c) {
  const std::vector<char> flags = nodes_reached(cut, pieces, c.nodes, c.support);
  std::vector<Index> out;
  for (std::size_t I = 0; I < flags.size(); ++I)
    if (flags[I]) out.push_back(static_cast<Index>(I));
  return out;
}

/// Grows a grid rule piece by piece and checks, at each growth, the nodes it
/// reports against a grid built from scratch: unreported nodes keep their
/// old factor; every node's factor equals the fresh grid's.
/// `local`: some enriched nodes must keep their factor (the update is local).
void check_growth(const CutSurface& cut, const Cloud& c, GridLookup lookup, bool local) {
  const double spacing = 0.02;
  const Index first = cut.pieces_at(0.0);
  GridRule growing(cut, first, spacing, lookup, c.nodes, c.support, reached(cut, first, c));
  std::mt19937 random(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (Index pieces = first + 1; pieces <= cut.piece_count(); ++pieces) {
    // The factors before, at sample points in each node's support.
    std::vector<std::vector<Vec3>> samples(c.nodes.size());
    std::vector<std::vector<double>> before(c.nodes.size());
    for (std::size_t I = 0; I < c.nodes.size(); ++I) {
      if (distance_to_cut(cut, 0, cut.piece_count(), c.nodes[I]) > 2.0 * c.support[I]) continue;
      for (int s = 0; s < 12; ++s) {
        Vec3 d(u(random), u(random), cut.dimension == 3 ? u(random) : 0.0);
        if (d.norm() >= 1.0) continue;
        samples[I].push_back(c.nodes[I] + c.support[I] * d);
        before[I].push_back(growing.factor(static_cast<Index>(I), samples[I].back()).value);
      }
    }
    // The new piece reaches these nodes (what CutWeights finds with its k-d tree).
    std::vector<Index> new_reach;
    for (std::size_t I = 0; I < c.nodes.size(); ++I)
      if (distance_to_cut(cut, pieces - 1, pieces, c.nodes[I]) < c.support[I]) new_reach.push_back(static_cast<Index>(I));
    std::vector<Index> changed, everywhere;
    growing.grow(cut, pieces, new_reach, changed, &everywhere);
    std::vector<char> reported(c.nodes.size(), 0), whole_support(c.nodes.size(), 0);
    for (Index I : changed) reported[I] = 1;
    for (Index I : everywhere) {
      EXPECT_TRUE(reported[I]) << "node " << I << " changed everywhere but not reported";
      whole_support[I] = 1;
    }
    const GridRule fresh(cut, pieces, spacing, lookup, c.nodes, c.support, reached(cut, pieces, c));
    int kept = 0, unchanged_points = 0;
    for (std::size_t I = 0; I < c.nodes.size(); ++I) {
      const Index node = static_cast<Index>(I);
      ASSERT_EQ(growing.enriches(node), fresh.enriches(node)) << "node " << I << ", " << pieces << " pieces";
      for (std::size_t s = 0; s < samples[I].size(); ++s) {
        const double now = growing.factor(node, samples[I][s]).value;
        EXPECT_NEAR(now, fresh.factor(node, samples[I][s]).value, 1e-12) << "node " << I;
        // Where the factor changed, the growth says so: the node's whole support, or phi at the point.
        const bool may_change = whole_support[I] || growing.phi_may_have_changed(samples[I][s]);
        if (std::abs(now - before[I][s]) > 1e-12) {
          EXPECT_TRUE(may_change) << "node " << I << " changed at a point the growth calls unchanged, " << pieces
                                  << " pieces";
        }
        unchanged_points += !may_change;
        if (!reported[I]) {
          EXPECT_NEAR(now, before[I][s], 1e-12) << "node " << I << " changed unreported, " << pieces << " pieces";
          kept += growing.enriches(node);
        }
      }
    }
    EXPECT_FALSE(changed.empty());
    if (local) {
      EXPECT_GT(kept, 0) << "every enriched node was reported: the update is not local";
      EXPECT_GT(unchanged_points, 0) << "phi may have changed everywhere: the rows' filter is not local";
    }
  }
}

TEST(EnrichmentGrid, GrowingPolylineReportsEveryNodeWhoseFactorChanged) {
  check_growth(growing_polyline(), cloud(2, 0.05), GridLookup::exact, false);
  // A turning cut turns the lattice: interpolation then updates every enriched node.
  check_growth(growing_polyline(), cloud(2, 0.05), GridLookup::interpolated, false);
  // A straight one keeps it, and the interpolated update stays local.
  const CutSurface straight = cut_surface(
      2, {Vec3(-0.62, 0.013, 0), Vec3(-0.4, 0.013, 0), Vec3(-0.2, 0.013, 0), Vec3(0.1, 0.013, 0)}, {0, 0, 1, 2}, "");
  check_growth(straight, cloud(2, 0.05), GridLookup::interpolated, true);
}

TEST(EnrichmentGrid, GrowingStripReportsEveryNodeWhoseFactorChanged) {
  // A tilting strip turns its common plane: every edge's d+ changes.
  check_growth(growing_strip(), cloud(3, 0.1), GridLookup::exact, false);
  std::vector<Vec3> v;
  std::vector<double> t;
  for (int k = 0; k < 4; ++k) {
    v.emplace_back(-0.52 + 0.25 * k, -0.3, 0.013), v.emplace_back(-0.52 + 0.25 * k, 0.3, 0.013);
    t.push_back(std::max(0, 2 * k - 2)), t.push_back(std::max(0, 2 * k - 1));
  }
  const CutSurface flat = cut_surface(3, v, t, "flat strip");
  check_growth(flat, cloud(3, 0.1), GridLookup::exact, true);
  check_growth(flat, cloud(3, 0.1), GridLookup::interpolated, true);
}

TEST(EnrichmentGrid, InterpolatedPhiConvergesToTheExactAwayFromTheFaces) {
  const CutSurface cut = growing_polyline();
  std::mt19937 random(9);
  std::uniform_real_distribution<double> u(-0.7, 0.7);
  std::vector<Vec3> points;
  while (points.size() < 400) {
    const Vec3 x(u(random), 0.5 * u(random), 0);
    if (distance_to_cut(cut, 0, cut.piece_count(), x) > 0.1) points.push_back(x);
  }
  double previous = 0.0;
  for (double spacing : {0.04, 0.02, 0.01}) {
    const EnrichmentGrid grid(cut, cut.piece_count(), spacing, 0.3);
    double worst = 0.0;
    for (const Vec3& x : points) worst = std::max(worst, std::abs(grid.interpolated(x).value - grid.exact(x).value));
    if (previous > 0.0) {
      EXPECT_LT(worst, 0.35 * previous) << "spacing " << spacing;  // second order: 1/4
    }
    previous = worst;
  }
  EXPECT_LT(previous, 2e-3);
  // The jump across the faces stays sharp: s is exact, only d+ is interpolated.
  const EnrichmentGrid coarse(cut, cut.piece_count(), 0.04, 0.3);
  const CutPiece& middle = cut.pieces[2];
  for (double side : {1.0, -1.0}) {
    const Vec3 x = middle.centre + side * 1e-9 * middle.normal;
    EXPECT_NEAR(coarse.interpolated(x).value, side, 1e-9);
  }
  // Lattice points hold the exact phi.
  const EnrichmentGrid grid(cut, cut.piece_count(), 0.02, 0.3);
  const Vec3 corner = grid.lattice_origin();
  const Vec3 x = corner + 7 * 0.02 * grid.lattice_axes()[0] + 5 * 0.02 * grid.lattice_axes()[1];
  EXPECT_NEAR(grid.interpolated(x).value, grid.exact(x).value, 1e-12);
}

/// Does the ball (x, radius) reach a flagged column? Every column looked at.
bool scan_reaches(const EnrichmentGrid& grid, const Vec3& x, double radius) {
  const std::vector<char>& changed = grid.changed_columns();
  const auto& axes = grid.lattice_axes();
  const Index n0 = grid.lattice_count()[0];
  for (Index c = 0; c < static_cast<Index>(changed.size()); ++c) {
    if (!changed[c]) continue;
    const Vec3 d = grid.lattice_origin() + grid.spacing() * ((c % n0) * axes[0] + (c / n0) * axes[1]) - x;
    if (std::pow(axes[0].dot(d), 2) + std::pow(axes[1].dot(d), 2) < radius * radius) return true;
  }
  return false;
}

TEST(EnrichmentGrid, ReachesAChangedColumnWhereAScanOfEveryColumnDoes) {
  // The query looks only at the columns in the changed ones' box: it must
  // answer as a scan of every column does, for balls of every size anywhere.
  const CutSurface cut = growing_strip();
  std::mt19937 random(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0), r(0.005, 0.4);
  for (Index pieces = 2; pieces <= cut.piece_count(); ++pieces) {
    const EnrichmentGrid before(cut, pieces - 1, 0.02, 0.25);
    const EnrichmentGrid grown(cut, pieces, 0.02, 0.25, before);
    ASSERT_TRUE(grown.knows_changes());
    const std::vector<char>& changed = grown.changed_columns();
    const auto flagged = std::count(changed.begin(), changed.end(), 1);
    ASSERT_GT(flagged, 0) << pieces << " pieces";
    int reached = 0, missed = 0;
    for (int k = 0; k < 2000; ++k) {
      const Vec3 x(1.0 * u(random), 0.7 * u(random), 0.3 * u(random));  // past the lattice too
      const double radius = r(random);
      const bool expected = scan_reaches(grown, x, radius);
      ASSERT_EQ(grown.reaches_changed_column(x, radius), expected) << "x " << x.transpose() << ", radius " << radius;
      (expected ? reached : missed) += 1;
    }
    EXPECT_GT(reached, 100);
    EXPECT_GT(missed, 100);
  }
  EXPECT_FALSE(EnrichmentGrid(cut, 2, 0.02, 0.25).knows_changes());
}

TEST(EnrichmentGrid, RefusesALatticeTooLargeNamingTheKey) {
  const CutSurface cut = growing_strip();
  try {
    EnrichmentGrid grid(cut, cut.piece_count(), 1e-4, 0.2);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("grid.spacing"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("growing strip"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace kerf
