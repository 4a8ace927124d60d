// `fem: split`'s geometry (geometry/cell_fragments.h, geometry/cell_split.h):
// every side pattern of a simplex tiles it with the level set's volume; a
// plane through a body splits its volume exactly and leaves two pieces; the
// degenerate placements (a cut on mesh faces, through a node) duplicate nodes
// without slivers; a front inside the body keeps the material joined.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>

#include "geometry/cell_fragments.h"
#include "geometry/cell_split.h"
#include "support/cut_geometry.h"
#include "support/test_support.h"

namespace kerf {
namespace {

/// The divided difference of max(x, 0)^(dim): the share of the simplex where
/// the linear function with corner values phi is positive (distinct values).
double positive_share(int dim, const std::array<double, 4>& phi) {
  double share = 0.0;
  for (int a = 0; a <= dim; ++a) {
    if (phi[a] <= 0) continue;
    double term = std::pow(phi[a], dim);
    for (int b = 0; b <= dim; ++b)
      if (b != a) term /= phi[a] - phi[b];
    share += term;
  }
  return share;
}

void expect_every_pattern_tiles(int dim, const std::array<Vec3, 4>& corners) {
  const double measure = simplex_measure(dim, corners.data());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> magnitude(0.2, 1.0);
  int patterns = 0;
  for (int code = 0; code < (dim == 3 ? 81 : 27); ++code) {
    std::array<int, 4> side{};
    std::array<double, 4> phi{};
    bool plus = false, minus = false;
    for (int k = 0, rest = code; k <= dim; ++k, rest /= 3) {
      side[k] = rest % 3 - 1;
      phi[k] = side[k] * magnitude(random);
      plus |= side[k] > 0;
      minus |= side[k] < 0;
    }
    if (!plus || !minus) continue;
    ++patterns;
    const CellFragments f = cell_fragments(dim, corners, side, [&](int a, int b) {
      return Vec3(corners[a] + phi[a] / (phi[a] - phi[b]) * (corners[b] - corners[a]));
    });
    std::array<double, 2> share{};
    for (int s = 0; s < 2; ++s)
      for (std::size_t k = 0; k < f.simplices[s].size(); k += dim + 1) {
        const double m = simplex_measure(dim, &f.simplices[s][k]);
        EXPECT_GT(m, 0.0) << "pattern " << code << " side " << s;
        share[s] += m / measure;
      }
    EXPECT_NEAR(share[0] + share[1], 1.0, 1e-14) << "pattern " << code;
    EXPECT_NEAR(share[0], positive_share(dim, phi), 1e-12) << "pattern " << code;
  }
  EXPECT_EQ(patterns, dim == 3 ? 50 : 12);  // 3^n, less the 2^n with no + and the 2^n with no -, plus all-zero
}

TEST(CellFragments, EverySidePatternTilesTheTetrahedronAsTheLevelSetDoes) {
  expect_every_pattern_tiles(3, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)});
  expect_every_pattern_tiles(3, {Vec3(0.1, 0.2, -0.3), Vec3(2.0, 0.4, 0.1), Vec3(0.7, 1.3, 0.2), Vec3(0.9, 0.5, 0.8)});
}

TEST(CellFragments, EverySidePatternTilesTheTriangleAsTheLevelSetDoes) {
  expect_every_pattern_tiles(2, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3::Zero()});
  expect_every_pattern_tiles(2, {Vec3(0.1, 0.2, 0), Vec3(2.0, 0.4, 0), Vec3(0.7, 1.3, 0), Vec3::Zero()});
}

std::vector<CutPiece> plane_pieces(const Vec3& n, double d) { return testing::plane_cut(3, n, d); }

/// Each cell's part of the body, measured where its sub-simplices lie: the
/// totals on the + and - sides of n . x = d.
std::array<double, 2> side_measures(const CellSplit& split, const Mesh& original, const Vec3& n, double d) {
  const int dim = original.dimension;
  const double reference = dim == 3 ? 1.0 / 6.0 : 0.5;
  std::array<double, 2> total{};
  for (Index c = 0; c < split.mesh.cell_count(); ++c) {
    const auto cell = original.cell(split.parent[c]);
    const Vec3 x0 = original.nodes[cell[0]];
    Eigen::Matrix3d J = Eigen::Matrix3d::Identity();
    for (int i = 0; i < dim; ++i)
      for (int k = 0; k < dim; ++k) J(i, k) = original.nodes[cell[k + 1]][i] - x0[i];
    const double measure = cell_measure(original, split.parent[c]);
    if (split.whole(c)) {
      Vec3 centre = Vec3::Zero();
      for (int k = 0; k <= dim; ++k) centre += original.nodes[cell[k]] / (dim + 1);
      total[n.dot(centre) > d ? 0 : 1] += measure;
      continue;
    }
    const auto xi = split.fragment(c);
    for (std::size_t k = 0; k < xi.size(); k += dim + 1) {
      Vec3 centre = Vec3::Zero();
      for (int v = 0; v <= dim; ++v) centre += (x0 + J * xi[k + v]) / (dim + 1);
      total[n.dot(centre) > d ? 0 : 1] += simplex_measure(dim, &xi[k]) / reference * measure;
    }
  }
  return total;
}

int pieces(const Mesh& mesh) {
  const std::vector<int> label = testing::node_pieces(mesh);
  return *std::max_element(label.begin(), label.end()) + 1;
}

/// Neither snapping nor dropping: the fragments are the cut's exactly.
const SplitOptions exact{0.0, 0.0};

// x + 0.3 y + 0.2 z = 0.6 crosses the unit cube with x between 0.1 and 0.6:
// the side below holds 0.35 of it. Snapping moves the cut onto nodes within
// 0.05 of their shortest edge (0.2 here): at most that slab changes side.
TEST(CellSplit, AnObliquePlaneSplitsTheBoxVolumeExactlyIntoTwoPieces) {
  for (int order : {1, 2}) {
    const Mesh mesh = testing::unit_box_mesh(3, order, 0.2);
    const Vec3 n(1, 0.3, 0.2);
    const CellSplit split = split_cells(mesh, plane_pieces(n, 0.6), exact);
    EXPECT_GT(split.separated_cells, 10);
    EXPECT_GT(split.duplicated_nodes, 10);
    const auto [above, below] = side_measures(split, mesh, n, 0.6);
    EXPECT_NEAR(below, 0.35, 1e-12) << "order " << order;
    EXPECT_NEAR(above, 0.65, 1e-12) << "order " << order;
    EXPECT_EQ(pieces(split.mesh), 2) << "order " << order;
    for (Index k = mesh.node_count(); k < split.mesh.node_count(); ++k)
      EXPECT_EQ(split.mesh.nodes[k], mesh.nodes[split.origin[k]]);
    const CellSplit snapped = split_cells(mesh, plane_pieces(n, 0.6));
    const auto [snapped_above, snapped_below] = side_measures(snapped, mesh, n, 0.6);
    EXPECT_NEAR(snapped_above + snapped_below + snapped.dropped_measure, 1.0, 1e-12);  // nothing lost unsaid
    EXPECT_NEAR(snapped_below, 0.35, 0.05 * 0.2 * 1.2) << "order " << order;
    EXPECT_EQ(pieces(snapped.mesh), 2) << "order " << order;
  }
}

TEST(CellSplit, AnObliqueLineSplitsThePlateAreaExactlyIntoTwoPieces) {
  const Mesh mesh = testing::unit_box_mesh(2, 1, 0.1);
  const Vec3 n(1, 0.15, 0);  // x + 0.15 y = 0.475
  const CellSplit split = split_cells(mesh, testing::plane_cut(2, n, 0.475), exact);
  const auto [right, left] = side_measures(split, mesh, n, 0.475);
  EXPECT_NEAR(left + right, 1.0, 1e-13);
  EXPECT_NEAR(left, 0.475 - 0.075, 1e-12);
  EXPECT_EQ(pieces(split.mesh), 2);
}

// The plane x = 0.5 of the Kuhn cubes is made of cell faces: no cell is
// separated, the nodes on it are duplicated, and the two halves come apart.
TEST(CellSplit, ACutLyingOnCellFacesSplitsNoCellAndDuplicatesTheFacesNodes) {
  const Mesh mesh = testing::kuhn_cubes(4, 0.25);
  const CellSplit split = split_cells(mesh, plane_pieces(Vec3(1, 0, 0), 0.5));
  EXPECT_EQ(split.separated_cells, 0);
  EXPECT_EQ(split.duplicated_nodes, 25);
  EXPECT_EQ(split.mesh.cell_count(), mesh.cell_count());
  EXPECT_EQ(pieces(split.mesh), 2);
}

// A plane through the node (0.5, 0.5, 0.5) and no other: the node is
// duplicated, and snapping leaves no fragment thinner than its rule allows.
TEST(CellSplit, ACutThroughANodeDuplicatesItAndLeavesNoSliver) {
  const Mesh mesh = testing::kuhn_cubes(4, 0.25);
  const Vec3 n(1, 0.37, 0.23);
  const CellSplit split = split_cells(mesh, plane_pieces(n, n.dot(Vec3(0.5, 0.5, 0.5))));
  Index centre = -1;
  for (Index k = 0; k < mesh.node_count(); ++k)
    if ((mesh.nodes[k] - Vec3(0.5, 0.5, 0.5)).norm() < 1e-12) centre = k;
  const Index copies = std::count(split.origin.begin(), split.origin.end(), centre);
  EXPECT_EQ(copies, 2);
  EXPECT_EQ(pieces(split.mesh), 2);
  EXPECT_GT(split.smallest_fraction, 1e-4);
  const auto [above, below] = side_measures(split, mesh, n, n.dot(Vec3(0.5, 0.5, 0.5)));
  EXPECT_NEAR(above + below, 1.0, 1e-12);
}

// x + 2 y = 1.5 holds three columns of the Kuhn cubes' nodes and their
// vertical edges, and crosses the other cells through their interiors: the
// edges' nodes are duplicated, the cells beside them split, no sliver left.
TEST(CellSplit, ACutAlongEdgesDuplicatesTheirNodesAndSplitsTheCellsItCrosses) {
  const Mesh mesh = testing::kuhn_cubes(4, 0.25);
  const Vec3 n(1, 2, 0);
  const CellSplit split = split_cells(mesh, plane_pieces(n, 1.5), exact);
  Index on_plane = 0;
  for (Index k = 0; k < mesh.node_count(); ++k) on_plane += std::abs(n.dot(mesh.nodes[k]) - 1.5) < 1e-12;
  EXPECT_EQ(on_plane, 15);
  for (Index k = 0; k < mesh.node_count(); ++k) {
    if (std::abs(n.dot(mesh.nodes[k]) - 1.5) < 1e-12) {
      EXPECT_EQ(std::count(split.origin.begin(), split.origin.end(), k), 2) << "node " << k;
    }
  }
  EXPECT_GT(split.separated_cells, 0);
  EXPECT_EQ(pieces(split.mesh), 2);
  const auto [above, below] = side_measures(split, mesh, n, 1.5);
  // Below x + 2 y = 1.5 in the unit cube: the integral over y of clamp(1.5 - 2 y, 0, 1).
  EXPECT_NEAR(below, 0.25 + 0.5 * 0.5, 1e-12);
  EXPECT_NEAR(above + below, 1.0, 1e-12);
}

// The same cut on the same mesh with its cells listed in another order: the
// same copies, node for node (new nodes numbered by their original's id and
// side, never by the order cells come in).
TEST(CellSplit, TheSplitDoesNotDependOnTheCellsOrder) {
  const Mesh mesh = testing::unit_box_mesh(3, 2, 0.2);
  Mesh shuffled = mesh;
  std::vector<Index> order(mesh.cell_count());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(3));
  const int npc = mesh.nodes_per_cell();
  for (Index c = 0; c < mesh.cell_count(); ++c)
    std::copy(mesh.cell(order[c]).begin(), mesh.cell(order[c]).end(), shuffled.cells.begin() + c * npc);
  const std::vector<CutPiece> cut = plane_pieces(Vec3(1, 0.3, 0.2), 0.6);
  const CellSplit a = split_cells(mesh, cut), b = split_cells(shuffled, cut);
  ASSERT_EQ(a.mesh.node_count(), b.mesh.node_count());
  EXPECT_EQ(a.origin, b.origin);
  EXPECT_EQ(a.phantom, b.phantom);
  // Each parent's copies, as node tuples with their side, match.
  std::map<std::pair<Index, int>, std::vector<Index>> copies_a, copies_b;
  for (Index c = 0; c < a.mesh.cell_count(); ++c) {
    const auto cell = a.mesh.cell(c);
    copies_a[{a.parent[c], a.side[c]}].assign(cell.begin(), cell.end());
  }
  for (Index c = 0; c < b.mesh.cell_count(); ++c) {
    const auto cell = b.mesh.cell(c);
    copies_b[{order[b.parent[c]], b.side[c]}].assign(cell.begin(), cell.end());
  }
  EXPECT_TRUE(copies_a == copies_b);
}

// The plane 0.3 x + y + 0.2 z = 0.75 holds the node (0.5, 0.5, 0.5); the cut
// is its part at x <= 0.5, so its front runs through that node. The body
// stays one piece and no node at or beyond the front is copied on its side.
TEST(CellSplit, AFrontThroughANodeLeavesTheNodeJoined) {
  const Mesh mesh = testing::kuhn_cubes(4, 0.25);
  const Vec3 n(0.3, 1, 0.2);
  const double d = n.dot(Vec3(0.5, 0.5, 0.5));
  const auto at = [&](double x, double z) { return Vec3(x, (d - n.x() * x - n.z() * z) / n.y(), z); };
  const std::vector<CutPiece> cut{testing::triangle_piece(at(-0.5, -0.5), at(0.5, -0.5), at(0.5, 1.5)),
                                  testing::triangle_piece(at(-0.5, -0.5), at(0.5, 1.5), at(-0.5, 1.5))};
  const CellSplit split = split_cells(mesh, cut);
  EXPECT_GT(split.duplicated_nodes, 0);
  EXPECT_EQ(pieces(split.mesh), 1);
  // Phantoms (copies extending a far side's field) may sit at the front; no
  // material copy does, the node on the front least of all.
  Index front_node_copies = 0;
  for (Index k = mesh.node_count(); k < split.mesh.node_count(); ++k) {
    if (!split.phantom[k]) {
      EXPECT_LT(split.mesh.nodes[k].x(), 0.5 - 1e-12) << "node " << k;
    }
    front_node_copies += (split.mesh.nodes[k] - Vec3(0.5, 0.5, 0.5)).norm() < 1e-12;
  }
  EXPECT_EQ(front_node_copies, 0);
}

// A plane through nodes, and the same plane moved 1e-9 of a cell off them:
// the split volumes move with it continuously (snapping keeps the cut on the
// nodes; without it, the slivers the move makes are as thin as the move).
TEST(CellSplit, MovingTheCutAHairOffTheNodesMovesTheAnswerAHair) {
  const Mesh mesh = testing::kuhn_cubes(4, 0.25);
  const Vec3 n(1, 2, 0);
  for (const SplitOptions& options : {SplitOptions{}, exact}) {
    const auto below = [&](double d) { return side_measures(split_cells(mesh, plane_pieces(n, d), options), mesh, n, d)[1]; };
    const double on = below(1.5);
    for (double shift : {-1e-9 * 0.25, 1e-9 * 0.25})
      EXPECT_NEAR(below(1.5 + shift), on, 1e-8) << "snap " << options.snap << ", shift " << shift;
  }
}

// A cut from the face x = 0 to x = 0.5 (its front inside the box): the body
// stays one piece; no node at or beyond the front is duplicated.
TEST(CellSplit, AFrontInsideTheBodyKeepsTheMaterialJoinedBeyondIt) {
  const Mesh mesh = testing::unit_box_mesh(3, 1, 0.1);
  const double front = 0.5;
  const Vec3 a(-0.5, 0.43, -0.5), b(front, 0.43, -0.5), c(front, 0.43, 1.5), d(-0.5, 0.43, 1.5);
  const std::vector<CutPiece> cut{testing::triangle_piece(a, b, c), testing::triangle_piece(a, c, d)};
  const CellSplit split = split_cells(mesh, cut);
  EXPECT_GT(split.separated_cells, 20);
  EXPECT_EQ(pieces(split.mesh), 1);
  for (Index k = mesh.node_count(); k < split.mesh.node_count(); ++k)
    EXPECT_LT(split.mesh.nodes[k].x(), front) << "node " << k;
}

}  // namespace
}  // namespace kerf
