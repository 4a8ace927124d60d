// A rank's piece of a snapshot: its cells, only the points they use, the
// fields cut to match, and the cell field `rank`.
#include <gtest/gtest.h>

#include "output/snapshot_piece.h"

namespace kerf {
namespace {

// Three triangles in a row over points 0..4: (0,1,2) (1,3,2) (3,4,2); a
// point field = the point's index, a cell field = 10 x the cell's.
BodySnapshot three_triangles() {
  BodySnapshot s;
  for (int p = 0; p < 5; ++p) s.points.push_back(Vec3(p, p % 2, 0));
  s.connectivity = {0, 1, 2, 1, 3, 2, 3, 4, 2};
  s.offsets = {3, 6, 9};
  s.cell_types = {5, 5, 5};
  s.point_fields.push_back({"index", 1, {0, 1, 2, 3, 4}});
  s.cell_fields.push_back({"tens", 2, {0, 0, 10, 10, 20, 20}});
  return s;
}

TEST(SnapshotPiece, HoldsItsCellsThePointsTheyUseAndTheirFields) {
  const BodySnapshot piece = snapshot_piece(three_triangles(), {1, 3}, 2);
  ASSERT_EQ(piece.points.size(), 4u);  // 1, 2, 3, 4: point 0 is not used
  EXPECT_EQ(piece.points[0], Vec3(1, 1, 0));
  EXPECT_EQ(piece.connectivity, (std::vector<Index>{0, 2, 1, 2, 3, 1}));
  EXPECT_EQ(piece.offsets, (std::vector<Index>{3, 6}));
  EXPECT_EQ(piece.cell_types.size(), 2u);
  EXPECT_EQ(piece.point_fields[0].values, (std::vector<double>{1, 2, 3, 4}));
  EXPECT_EQ(piece.cell_fields[0].values, (std::vector<double>{10, 10, 20, 20}));
  ASSERT_EQ(piece.cell_fields.size(), 2u);
  EXPECT_EQ(piece.cell_fields[1].name, "rank");
  EXPECT_EQ(piece.cell_fields[1].values, (std::vector<double>{2, 2}));
}

TEST(SnapshotPiece, AnEmptyRangeIsAnEmptyPieceAndARangeBeyondTheCellsIsRefused) {
  const BodySnapshot piece = snapshot_piece(three_triangles(), {3, 3}, 0);
  EXPECT_TRUE(piece.points.empty());
  EXPECT_TRUE(piece.cell_types.empty());
  EXPECT_THROW(snapshot_piece(three_triangles(), {2, 4}, 0), std::exception);
}

}  // namespace
}  // namespace kerf
