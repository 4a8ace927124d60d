// A cut piece clipped by the cells of a simplex mesh (geometry/cut_in_cells.h):
// the parts partition the piece inside the mesh wherever it lies, also on
// cell faces, along edges and through nodes, where each part belongs to the
// cell the piece's normal points into.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "geometry/cut_in_cells.h"
#include "support/cut_geometry.h"

namespace kerf {
namespace {

Mesh kuhn_cubes() { return testing::kuhn_cubes(2, 1.0); }  // the planes x, y, z = 1 hold nodes

CutPiece piece(const Vec3& a, const Vec3& b, const Vec3& c) { return testing::triangle_piece(a, b, c); }

std::vector<Index> every_cell(const Mesh& mesh) {
  std::vector<Index> cells(mesh.cell_count());
  std::iota(cells.begin(), cells.end(), 0);
  return cells;
}

double parts_measure(const std::vector<CutPart>& parts) {
  double sum = 0.0;
  PartPoints points;
  for (const CutPart& part : parts) {
    part_quadrature(part, 3, points);
    for (double w : points.weight) sum += w;
  }
  return sum;
}

Vec3 centroid(const Mesh& mesh, Index c) {
  Vec3 x = Vec3::Zero();
  for (Index n : mesh.cell(c)) x += mesh.nodes[n] / 4.0;
  return x;
}

TEST(CutInCells, PartsOfAPieceInsideTheMeshAddUpToIt) {
  const Mesh mesh = kuhn_cubes();
  const CutPiece p = piece({0.13, 0.21, 0.37}, {1.71, 0.43, 1.12}, {0.52, 1.83, 1.61});
  const auto parts = cut_parts(mesh, every_cell(mesh), p, 1e-9);
  EXPECT_GT(parts.size(), 8u);
  EXPECT_NEAR(parts_measure(parts), p.size, 1e-12 * p.size);
}

TEST(CutInCells, APieceOnCellFacesAndThroughNodesIsCountedOnceOnItsNormalsSide) {
  const Mesh mesh = kuhn_cubes();
  // On the plane z = 1 (cell faces), its corners on nodes, its edges along cell edges.
  for (const double up : {1.0, -1.0}) {
    const CutPiece p = up > 0 ? piece({0, 0, 1}, {2, 0, 1}, {2, 2, 1}) : piece({0, 0, 1}, {2, 2, 1}, {2, 0, 1});
    const auto parts = cut_parts(mesh, every_cell(mesh), p, 1e-9);
    EXPECT_NEAR(parts_measure(parts), 2.0, 1e-12);
    for (const CutPart& part : parts) EXPECT_GT(up * (centroid(mesh, part.cell).z() - 1.0), 0.0);
  }
  // Inside: along the cubes' shared diagonal edge through the node (1, 1, 1), across x, y, z = 1.
  const CutPiece slanted = piece({0.5, 0.5, 0.5}, {1.5, 1.5, 1.5}, {1.6, 0.3, 0.9});
  EXPECT_NEAR(parts_measure(cut_parts(mesh, every_cell(mesh), slanted, 1e-9)), slanted.size, 1e-12 * slanted.size);
  // Reaching the mesh's boundary, the piece counts as moved by the hair there.
  const CutPiece to_boundary = piece({1, 0, 0}, {0.2, 2, 0.5}, {1, 2, 2});
  EXPECT_NEAR(parts_measure(cut_parts(mesh, every_cell(mesh), to_boundary, 1e-9)), to_boundary.size, 1e-8);
}

TEST(CutInCells, APieceReachingOutOfTheMeshKeepsItsPartInside) {
  const Mesh mesh = kuhn_cubes();
  // z = 0.5, over [-1, 3] x [-1, 3]: inside, the 2 x 2 square.
  const CutPiece a = piece({-1, -1, 0.5}, {3, -1, 0.5}, {3, 3, 0.5}), b = piece({-1, -1, 0.5}, {3, 3, 0.5}, {-1, 3, 0.5});
  EXPECT_NEAR(parts_measure(cut_parts(mesh, every_cell(mesh), a, 1e-9)) +
                  parts_measure(cut_parts(mesh, every_cell(mesh), b, 1e-9)),
              4.0, 1e-12);
}

TEST(CutInCells, CellsNearNodesAreThoseAroundThem) {
  const Mesh mesh = kuhn_cubes();
  const NodeCells around = node_cells(mesh);
  const std::vector<Index> nodes = {0, 1 + 3 + 9, 2 + 3 * 1};  // (0,0,0) (1,1,1) (2,1,0)
  std::vector<Index> expected;
  for (Index c = 0; c < mesh.cell_count(); ++c)
    for (Index n : mesh.cell(c))
      if (std::find(nodes.begin(), nodes.end(), n) != nodes.end()) {
        expected.push_back(c);
        break;
      }
  EXPECT_EQ(cells_near(around, nodes), expected);
  EXPECT_EQ(cells_near(around, std::vector<Index>{0}).size(), 6u);  // the corner: one cube's tets
}

}  // namespace
}  // namespace kerf
