// The nodal volumes split by a cut (visible_dual_cells.h): without a cut they
// are the dual cells' own; with a cut through the whole body every node's
// volume lies on its own side, so each side's nodes hold that side's volume.
#include <gtest/gtest.h>

#include <numeric>
#include <random>

#include "discretization/meshless/node_set.h"
#include "discretization/meshless/visible_dual_cells.h"
#include "geometry/cut_surface.h"
#include "geometry/delaunay_mesh.h"

namespace kerf {
namespace {

/// A strip of two triangles spanning the plane through `origin` with in-plane
/// directions u and v, far beyond the unit box.
CutSurface plane_cut(const Vec3& origin, const Vec3& u, const Vec3& v) {
  const double far = 5.0;
  return cut_surface(3,
                     {origin - far * u - far * v, origin - far * u + far * v, origin + far * u - far * v,
                      origin + far * u + far * v},
                     {0, 0, 0, 0}, "test cut");
}

/// Each side's nodes' volume (+ side: normal . (x - o) >= 0, nodes on the cut included).
std::array<double, 2> side_volumes(const NodeSet& nodes, const std::vector<double>& volume, const CutSurface& cut) {
  const CutPiece& piece = cut.pieces[0];
  std::array<double, 2> sides{0.0, 0.0};
  for (Index I = 0; I < nodes.size(); ++I) {
    const double s = piece.normal.dot(nodes.positions[I] - piece.corner[0]);
    sides[s >= -1e-12 ? 0 : 1] += volume[I];
  }
  return sides;
}

std::vector<Index> all_cells(const Mesh& mesh) {
  std::vector<Index> cells(mesh.cell_count());
  std::iota(cells.begin(), cells.end(), Index{0});
  return cells;
}

NodeSet unit_box_nodes(double h) { return lattice_nodes(3, Box{Vec3(0, 0, 0), Vec3(1, 1, 1)}, h, {}, 2.2); }

TEST(VisibleDualCells, WithoutACutAreTheDualCells) {
  const NodeSet nodes = unit_box_nodes(0.25);
  VisibleDualCells cells(nodes.cells);
  EXPECT_TRUE(cells.update(nodes.cells, all_cells(nodes.cells), {}).empty());
  const std::vector<Vec3> moments = dual_cell_second_moments(nodes.cells);
  for (Index I = 0; I < nodes.size(); ++I) {
    EXPECT_DOUBLE_EQ(cells.volume()[I], nodes.volume[I]) << I;
    EXPECT_NEAR((cells.second_moment()[I] - moments[I]).norm(), 0.0, 1e-14 * moments[I].norm()) << I;
  }
}

TEST(VisibleDualCells, EachSideOfACutBetweenNodePlanesHoldsItsVolume) {
  const NodeSet nodes = unit_box_nodes(0.25);
  const CutSurface cut = plane_cut(Vec3(0.4, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1));  // normal -x
  VisibleDualCells cells(nodes.cells);
  EXPECT_FALSE(cells.update(nodes.cells, all_cells(nodes.cells), cut.pieces).empty());
  const std::array<double, 2> sides = side_volumes(nodes, cells.volume(), cut);
  // + side (the normal's, -x): x < 0.4. Plain dual cells give it 0.375 (0.25
  // + half of 0.25). The refinement (depth 4) resolves the parts' boundaries
  // to 1/16 of a piece of the barycentric subdivision: measured 4.2e-5 off.
  ASSERT_LT(cut.pieces[0].normal.x(), 0.0);
  EXPECT_NEAR(sides[0], 0.4, 2e-4);
  EXPECT_NEAR(sides[1], 0.6, 2e-4);
  EXPECT_NEAR(std::accumulate(cells.volume().begin(), cells.volume().end(), 0.0), 1.0, 1e-12);
}

TEST(VisibleDualCells, ANodeOnTheCutKeepsOnlyThePlusSide) {
  const NodeSet nodes = unit_box_nodes(0.25);
  const CutSurface cut = plane_cut(Vec3(0.5, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0));  // normal +x, nodes on it
  VisibleDualCells cells(nodes.cells);
  cells.update(nodes.cells, all_cells(nodes.cells), cut.pieces);
  const std::array<double, 2> sides = side_volumes(nodes, cells.volume(), cut);
  EXPECT_NEAR(sides[0], 0.5, 1e-12);
  EXPECT_NEAR(sides[1], 0.5, 1e-12);
  ASSERT_GT(cut.pieces[0].normal.x(), 0.0);
  for (Index I = 0; I < nodes.size(); ++I)  // the plane's nodes lose their cells' -x parts
    if (std::abs(nodes.positions[I].x() - 0.5) < 1e-12) {
      EXPECT_LT(cells.volume()[I], 0.9 * nodes.volume[I]) << I;
      EXPECT_GT(cells.volume()[I], 0.1 * nodes.volume[I]) << I;
    }
}

TEST(VisibleDualCells, ATiltedCutThroughAnIrregularNodeSetSplitsTheVolumeExactly) {
  // Jittered lattice nodes, their Delaunay cells, and the plane x + 0.3 y = 0.47:
  // the + side (normal along (1, 0.3, 0)) holds x + 0.3 y > 0.47, of volume
  // 1 - int_0^1 (0.47 - 0.3 y) dy = 0.68 exactly.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::vector<Vec3> points;
  const int n = 6;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) {
        Vec3 x(i, j, k);
        for (int a = 0; a < 3; ++a)
          if (x[a] > 0 && x[a] < n) x[a] += jitter(random);
        points.push_back(x / n);
      }
  Mesh mesh = delaunay_mesh(points, 3);
  NodeSet nodes;
  nodes.positions = mesh.nodes;
  const Vec3 u = Vec3(0.3, -1.0, 0).normalized(), v(0, 0, 1);
  const CutSurface cut = plane_cut(Vec3(0.47, 0, 0), u, v);
  ASSERT_GT(cut.pieces[0].normal.x(), 0.0);
  VisibleDualCells cells(mesh);
  cells.update(mesh, all_cells(mesh), cut.pieces);
  const std::array<double, 2> sides = side_volumes(nodes, cells.volume(), cut);
  // The refinement (depth 4) resolves the parts' boundaries to 1/16 of a
  // piece of the barycentric subdivision.
  EXPECT_NEAR(sides[0], 0.68, 2e-4);
  EXPECT_NEAR(sides[1], 0.32, 2e-4);
  EXPECT_NEAR(std::accumulate(cells.volume().begin(), cells.volume().end(), 0.0), 1.0, 1e-12);
}

}  // namespace
}  // namespace kerf
