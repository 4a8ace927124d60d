// Cut geometry: pieces and their growth in time, the checks that refuse
// degenerate cuts (zero-length segment, collapsed triangle, a cut folding over
// its common line or plane), the common frame, regions and d+, crossings.
#include <gtest/gtest.h>

#include "core/check.h"
#include "geometry/cut_surface.h"
#include "support/test_support.h"

namespace kerf {
namespace {

std::string error_of(int dim, std::vector<Vec3> v) {
  try {
    cut_surface(dim, v, std::vector<double>(v.size(), 0.0), "scene.yaml:7: cuts.0");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CutSurface, PiecesAppearWithTheirLastVertex) {
  CutSurface c = cut_surface(2, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0.2, 0), Vec3(3, 0, 0)}, {0, 0, 0.5, 1.0}, "");
  ASSERT_EQ(c.piece_count(), 3);
  EXPECT_EQ(c.pieces_at(0.0), 1);
  EXPECT_EQ(c.pieces_at(0.7), 2);
  EXPECT_EQ(c.pieces_at(1.0), 3);
  EXPECT_NEAR(c.pieces[0].normal.y(), 1.0, 1e-15);  // left of the direction of travel
}

TEST(CutSurface, RefusesDegenerateInputNamingWhereAndWhat) {
  std::string e = error_of(2, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)});
  EXPECT_NE(e.find("scene.yaml:7: cuts.0"), std::string::npos) << e;
  EXPECT_NE(e.find("vertex 1"), std::string::npos) << e;
  EXPECT_NE(e.find("zero length"), std::string::npos) << e;
  e = error_of(3, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0)});
  EXPECT_NE(e.find("collapsed"), std::string::npos) << e;
  // A polyline that turns back on itself folds over its common line.
  e = error_of(2, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.2, 0.1, 0)});
  EXPECT_NE(e.find("folds over its common line"), std::string::npos) << e;
  EXPECT_NE(e.find("segment 1"), std::string::npos) << e;
  // A strip whose last triangle turns back over the others folds over its plane.
  e = error_of(3, {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0.5, 0, 0.1), Vec3(0.5, 1, 0.1)});
  EXPECT_NE(e.find("folds over its common plane"), std::string::npos) << e;
  // A zigzag within 87 degrees of its mean direction is accepted.
  EXPECT_EQ(error_of(2, {Vec3(0, 0, 0), Vec3(1, 0.5, 0), Vec3(2, 0, 0), Vec3(3, 0.5, 0)}), "");
}

TEST(CutSurface, StripTrianglesAreOrientedAlike) {
  CutSurface c = cut_surface(3, {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(2, 0, 0)},
                             std::vector<double>(5, 0.0), "");
  for (const CutPiece& p : c.pieces) EXPECT_NEAR(p.normal.dot(c.pieces[0].normal), 1.0, 1e-15);
  const CutFrame f = common_frame(c, 0, c.piece_count());
  EXPECT_NEAR(std::abs(f.normal.z()), 1.0, 1e-15);
}

TEST(CutSurface, RegionsAndDistanceFromTheEndsIn2D) {
  // A kinked polyline: d+ is measured from its two ends along the common line.
  CutSurface c = cut_surface(2, {Vec3(0, 0, 0), Vec3(1, 0.2, 0), Vec3(2, 0, 0)}, {0, 0, 0}, "");
  const CutFrame f = common_frame(c, 0, 2);
  EXPECT_NEAR(f.axis[0].x(), 1.0, 1e-15);  // symmetric kink: the mean angle is 0
  CutRegion r = cut_region(c, 0, 2, f, Vec3(0.5, 0.5, 0));
  EXPECT_EQ(r.piece, 0);
  EXPECT_EQ(r.d_plus, 0.0);
  EXPECT_GT(r.s, 0.0);
  r = cut_region(c, 0, 2, f, Vec3(1.5, -0.5, 0));
  EXPECT_EQ(r.piece, 1);
  EXPECT_LT(r.s, 0.0);
  r = cut_region(c, 0, 2, f, Vec3(2.5, 0.1, 0));
  EXPECT_EQ(r.piece, 1);
  EXPECT_NEAR(r.d_plus, 0.5, 1e-12);
}

// Ahead of a zigzag's tip, s is measured along the common normal from the
// end vertex: a point farther from the cut's line than the zigzag's amplitude
// keeps its side as pieces turning up and down appear (from the end
// segment's own line, steep here, it flipped with each piece), and s keeps
// its sign across the end's boundary t = t_end, where d+ = 0 makes phi = sign(s).
TEST(CutSurface, AheadOfAZigzagTipAPointKeepsItsSide) {
  std::vector<Vec3> v;
  for (int k = 0; k <= 12; ++k) v.push_back(Vec3(0.1 * k, k == 0 ? 0.0 : (k % 2 ? 0.1 : -0.1), 0));
  const CutSurface c = cut_surface(2, v, std::vector<double>(v.size(), 0.0), "");
  for (Index pieces = 2; pieces <= 12; ++pieces) {
    const CutFrame f = common_frame(c, 0, pieces);
    for (double y : {0.25, -0.25}) {
      const CutRegion r = cut_region(c, 0, pieces, f, Vec3(v[pieces].x() + 0.3, y, 0));
      EXPECT_GT(r.d_plus, 0.0);
      EXPECT_EQ(r.s > 0.0, y > 0.0) << pieces << " pieces, y = " << y;
    }
    for (double up : {0.05, -0.05}) {
      const Vec3 on = v[pieces] + up * f.normal;
      const CutRegion before = cut_region(c, 0, pieces, f, on - 1e-9 * f.axis[0]);
      const CutRegion after = cut_region(c, 0, pieces, f, on + 1e-9 * f.axis[0]);
      EXPECT_EQ(before.d_plus, 0.0);
      EXPECT_GT(after.d_plus, 0.0);
      EXPECT_EQ(before.s > 0.0, after.s > 0.0) << pieces << " pieces, " << up;
    }
  }
}

TEST(CutSurface, CrossingsAndDistances) {
  CutSurface c = cut_surface(3, {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)}, {0, 0, 0, 0}, "");
  EXPECT_TRUE(segment_crosses_cut(c, 0, 2, Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1)));
  EXPECT_FALSE(segment_crosses_cut(c, 0, 2, Vec3(1.5, 0.5, -1), Vec3(1.5, 0.5, 1)));
  EXPECT_FALSE(segment_crosses_cut(c, 0, 2, Vec3(0.5, 0.5, 0), Vec3(0.5, 0.5, 1)));  // touches at an end
  EXPECT_NEAR(distance_to_cut(c, 0, 2, Vec3(0.5, 0.5, 0.3)), 0.3, 1e-15);
  EXPECT_NEAR(distance_to_cut(c, 0, 2, Vec3(2, 0.5, 0)), 1.0, 1e-15);
}

}  // namespace
}  // namespace kerf

namespace kerf {
namespace {

TEST(CutSurface, GrownVertexByVertexIsTheCutGivenWholeAndARefusedPieceLeavesItAsItWas) {
  std::vector<Vec3> v;
  std::vector<double> t;
  for (int k = 0; k < 30; ++k) {
    v.push_back(Vec3(0.001 * k, 0.05 + 1e-4 * (k % 3), 0.11)), t.push_back(0.001 * k);
    v.push_back(Vec3(0.001 * k, 0.05, 0.03)), t.push_back(0.001 * k);
  }
  const CutSurface whole = cut_surface(3, v, t, "whole");
  CutSurface grown = cut_surface(3, {}, {}, "grown");
  for (int k = 0; k < 30; ++k) extend_cut_surface(grown, std::span<const Vec3>(v).subspan(2 * k, 2), t[2 * k]);
  ASSERT_EQ(grown.piece_count(), whole.piece_count());
  EXPECT_EQ(grown.extent, whole.extent);
  EXPECT_EQ(grown.appears, whole.appears);
  for (Index k = 0; k < whole.piece_count(); ++k) {
    EXPECT_EQ(grown.pieces[k].corner, whole.pieces[k].corner) << k;
    EXPECT_EQ(grown.pieces[k].normal, whole.pieces[k].normal) << k;
  }
  // A blade turned back over the strip folds it: refused, the cut as it was.
  const std::vector<Vec3> back{Vec3(0.01, 0.05, 0.12), Vec3(0.01, 0.06, 0.03)};
  const std::string error = testing::error_message([&] { extend_cut_surface(grown, back, 0.05); });
  EXPECT_NE(error.find("folds"), std::string::npos) << error;
  EXPECT_EQ(grown.piece_count(), whole.piece_count());
  EXPECT_EQ(grown.vertices, whole.vertices);
  EXPECT_EQ(grown.times, whole.times);
  EXPECT_EQ(grown.appears, whole.appears);
  // And a vertex earlier than the last one is refused.
  const std::vector<Vec3> early{Vec3(0.04, 0.05, 0.11)};
  EXPECT_NE(testing::error_message([&] { extend_cut_surface(grown, early, 0.0); }).find("before"), std::string::npos);
}

}  // namespace
}  // namespace kerf
