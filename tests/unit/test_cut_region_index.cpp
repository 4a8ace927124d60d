// The region index (geometry/cut_region_index.h) must give cut_region's
// answer bit for bit: the Enrichment Grid serves phi from it, and a run
// must not change with how the search is done. Checked on a long strip that
// bends and zigzags (so runs of pieces overlap on the plane), at random
// points, on the pieces' corners and edges, and beyond the ends.
#include <gtest/gtest.h>

#include <random>

#include "geometry/cut_region_index.h"

namespace kerf {
namespace {

/// A blade sweeping along x while tilting and bobbing: `positions` vertex pairs, many pieces per run.
CutSurface bent_strip(int positions) {
  std::vector<Vec3> v;
  for (int k = 0; k < positions; ++k) {
    const double x = 0.001 * k, bob = 0.004 * std::sin(0.3 * k), tilt = 0.002 * std::cos(0.17 * k);
    v.push_back(Vec3(x + tilt, 0.05 + 0.0005 * (k % 3), 0.11 + bob));
    v.push_back(Vec3(x, 0.05, 0.03 + bob));
  }
  return cut_surface(3, v, std::vector<double>(v.size(), 0.0), "test strip");
}

void expect_same_region(const CutRegion& a, const CutRegion& b, const Vec3& x) {
  ASSERT_EQ(a.piece, b.piece) << "at " << x.transpose();
  ASSERT_EQ(a.d_plus, b.d_plus) << "at " << x.transpose();
  ASSERT_EQ(a.d_plus_gradient, b.d_plus_gradient) << "at " << x.transpose();
  ASSERT_EQ(a.s, b.s) << "at " << x.transpose();
}

TEST(CutRegionIndex, GivesCutRegionsAnswerBitForBit) {
  const CutSurface cut = bent_strip(120);
  ASSERT_GT(cut.piece_count(), 10 * CutRegionIndex::pieces_per_run);
  for (const Index first : {Index{0}, Index{37}}) {
    const Index last = cut.piece_count();
    const CutFrame frame = common_frame(cut, first, last);
    const CutRegionIndex index(cut, first, last, frame);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> x(-0.03, 0.15), y(0.0, 0.1), z(0.0, 0.14);
    std::vector<Vec3> points;
    for (int i = 0; i < 4000; ++i) points.emplace_back(x(random), y(random), z(random));
    for (Index k = first; k < last; ++k)
      for (const Vec3& corner : cut.pieces[k].corner) {
        points.push_back(corner);
        points.push_back(0.5 * (corner + cut.pieces[k].corner[0]) + Vec3(0, 0.01, 0));  // an edge, off the plane
      }
    for (const Vec3& p : points) {
      expect_same_region(index.region(p), cut_region(cut, first, last, frame, p), p);
      EXPECT_LE(index.distance_bound(p), cut_region(cut, first, last, frame, p).d_plus * (1 + 1e-12) + 1e-18);
    }
  }
}

TEST(CutRegionIndex, PassesA2DCutToCutRegion) {
  const CutSurface cut = cut_surface(2, {Vec3(0, 0, 0), Vec3(1, 0.2, 0), Vec3(2, 0, 0)}, {0, 0, 0}, "");
  const CutFrame frame = common_frame(cut, 0, 2);
  const CutRegionIndex index(cut, 0, 2, frame);
  for (const Vec3& p : {Vec3(-0.5, 0.3, 0), Vec3(1.2, -0.1, 0), Vec3(2.5, 0.4, 0)})
    expect_same_region(index.region(p), cut_region(cut, 0, 2, frame, p), p);
}

}  // namespace
}  // namespace kerf
