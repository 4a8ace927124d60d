// The FEM baselines' meshes: `remesh` (gmsh conforming to the cut, its Crack
// plugin duplicating the nodes on it) and `remove` (cells the cut crosses deleted).
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "geometry/box_mesher.h"
#include "geometry/cut_cell_removal.h"
#include "geometry/cut_surface.h"

namespace kerf {
namespace {

std::vector<CutPiece> pieces_of(int dim, std::vector<Vec3> vertices) {
  CutSurface cut = cut_surface(dim, vertices, std::vector<double>(vertices.size(), 0.0), "test cut");
  return cut.pieces;
}

Mesh box_mesh(int dim, int order, double size, std::vector<CutPiece> cuts, Vec3 max = Vec3::Ones()) {
  BoxMeshRequest r;
  r.dimension = dim;
  r.order = order;
  r.max = max;
  if (dim == 2) r.max.z() = 0.0;
  r.size = size;
  r.cuts = std::move(cuts);
  return mesh_box(r);
}

/// Groups of nodes at one position (more than one: the crack duplicated them).
std::vector<std::vector<Index>> coincident_nodes(const Mesh& mesh) {
  std::map<std::tuple<double, double, double>, std::vector<Index>> at;
  for (Index n = 0; n < mesh.node_count(); ++n)
    at[{mesh.nodes[n].x(), mesh.nodes[n].y(), mesh.nodes[n].z()}].push_back(n);
  std::vector<std::vector<Index>> groups;
  for (auto& [x, nodes] : at)
    if (nodes.size() > 1) groups.push_back(nodes);
  return groups;
}

/// Cells with corners more than 1e-9 either side of the plane y = y0 whose
/// centroid lies between x0 and x1: a mesh conforming to a crack there has none.
Index cells_straddling(const Mesh& mesh, double y0, double x0, double x1);

Vec3 centroid(const Mesh& mesh, Index c) {
  Vec3 x = Vec3::Zero();
  for (int k = 0; k <= mesh.dimension; ++k) x += mesh.nodes[mesh.cell(c)[k]];
  return x / (mesh.dimension + 1);
}

Index cells_straddling(const Mesh& mesh, double y0, double x0, double x1) {
  Index count = 0;
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    bool above = false, below = false;
    for (int k = 0; k <= mesh.dimension; ++k) {
      above |= mesh.nodes[mesh.cell(c)[k]].y() > y0 + 1e-9;
      below |= mesh.nodes[mesh.cell(c)[k]].y() < y0 - 1e-9;
    }
    const double x = centroid(mesh, c).x();
    count += above && below && x > x0 && x < x1;
  }
  return count;
}

/// Each copy of a duplicated node is used only by cells on one side of the
/// plane y = y0 (the crack's), and the two copies by opposite sides.
void expect_copies_split_the_sides(const Mesh& mesh, const std::vector<Index>& copies, double y0) {
  std::map<Index, std::set<int>> sides;
  for (Index c = 0; c < mesh.cell_count(); ++c)
    for (Index n : mesh.cell(c))
      if (std::find(copies.begin(), copies.end(), n) != copies.end()) sides[n].insert(centroid(mesh, c).y() > y0 ? 1 : -1);
  ASSERT_EQ(sides.size(), 2u);
  std::set<int> all;
  for (auto& [n, s] : sides) {
    EXPECT_EQ(s.size(), 1u) << "a copy is used on both sides: node " << n << " at " << mesh.nodes[n].transpose();
    all.insert(s.begin(), s.end());
  }
  EXPECT_EQ(all.size(), 2u);
}

TEST(CutMeshing, RemeshDuplicatesTheNodesInsideACentreCrackButNotItsTips) {
  for (int order : {1, 2}) {
    const auto pieces = pieces_of(2, {Vec3(0.3, 0.5, 0), Vec3(0.5, 0.5, 0), Vec3(0.7, 0.5, 0)});
    Mesh mesh = box_mesh(2, order, 0.05, pieces);
    EXPECT_EQ(cells_straddling(mesh, 0.5, 0.3, 0.7), 0) << "the mesh conforms to the cut";
    const auto groups = coincident_nodes(mesh);
    EXPECT_GE(groups.size(), order == 1 ? 7u : 15u);  // 0.4 long at 0.05: 7 inner corners (and 8 mid-edges)
    for (const auto& g : groups) {
      ASSERT_EQ(g.size(), 2u);
      const Vec3& x = mesh.nodes[g[0]];
      EXPECT_NEAR(x.y(), 0.5, 1e-12);
      EXPECT_GT(x.x(), 0.3 + 1e-9);  // the tips stay joined
      EXPECT_LT(x.x(), 0.7 - 1e-9);
      expect_copies_split_the_sides(mesh, g, 0.5);
    }
  }
}

TEST(CutMeshing, RemeshOpensAnEdgeCrackAtTheSurfaceAndDropsWhatLiesOutside) {
  const auto pieces = pieces_of(2, {Vec3(-0.2, 0.5, 0), Vec3(0.5, 0.5, 0)});
  Mesh mesh = box_mesh(2, 1, 0.05, pieces);
  bool surface_opened = false;
  for (const auto& g : coincident_nodes(mesh)) {
    EXPECT_LT(mesh.nodes[g[0]].x(), 0.5 - 1e-9);
    surface_opened = surface_opened || std::abs(mesh.nodes[g[0]].x()) < 1e-12;
  }
  EXPECT_TRUE(surface_opened);
  for (const Vec3& x : mesh.nodes) EXPECT_GE(x.x(), -1e-12);
}

TEST(CutMeshing, RemeshOpensAThroughCrackInASlab) {
  // A strip crossing the slab's thickness (z) from x = 0.3 to 0.7 at y = 0.5.
  const auto pieces = pieces_of(3, {Vec3(0.3, 0.5, -0.1), Vec3(0.3, 0.5, 0.3), Vec3(0.7, 0.5, -0.1),
                                    Vec3(0.7, 0.5, 0.3)});
  Mesh mesh = box_mesh(3, 1, 0.1, pieces, Vec3(1, 1, 0.2));
  EXPECT_EQ(cells_straddling(mesh, 0.5, 0.3, 0.7), 0) << "the mesh conforms to the cut";
  const auto groups = coincident_nodes(mesh);
  EXPECT_GE(groups.size(), 3u);
  bool on_faces = false;
  for (const auto& g : groups) {
    const Vec3& x = mesh.nodes[g[0]];
    EXPECT_NEAR(x.y(), 0.5, 1e-12);
    EXPECT_GT(x.x(), 0.3 + 1e-9);
    EXPECT_LT(x.x(), 0.7 - 1e-9);
    on_faces = on_faces || x.z() < 1e-12 || x.z() > 0.2 - 1e-12;
    expect_copies_split_the_sides(mesh, g, 0.5);
  }
  EXPECT_TRUE(on_faces) << "the crack's edges on the slab's faces open too";
}

TEST(CutMeshing, TouchingIsNotCrossing) {
  Mesh tri;
  tri.dimension = 2;
  tri.nodes = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  tri.cells = {0, 1, 2};
  auto piece = [](Vec3 a, Vec3 b) { return pieces_of(2, {a, b})[0]; };
  EXPECT_TRUE(piece_crosses_cell(tri, 0, piece(Vec3(-1, 0.2, 0), Vec3(2, 0.2, 0))));
  EXPECT_TRUE(piece_crosses_cell(tri, 0, piece(Vec3(-1, 0.2, 0), Vec3(0.1, 0.2, 0))));  // a tip inside
  EXPECT_FALSE(piece_crosses_cell(tri, 0, piece(Vec3(-1, 0, 0), Vec3(2, 0, 0))));       // along an edge
  EXPECT_FALSE(piece_crosses_cell(tri, 0, piece(Vec3(-1, 1, 0), Vec3(0, 1, 0))));       // ends at a corner
  EXPECT_FALSE(piece_crosses_cell(tri, 0, piece(Vec3(-1, 0.2, 0), Vec3(0, 0.2, 0))));   // ends on an edge
  EXPECT_FALSE(piece_crosses_cell(tri, 0, piece(Vec3(1, 1, 0), Vec3(2, -1, 0))));       // misses
}

TEST(CutMeshing, RemoveDeletesTheCrossedCellsAndTheirOrphanNodes) {
  for (int dim : {2, 3}) {
    const auto pieces = dim == 2 ? pieces_of(2, {Vec3(0.3, 0.52, 0), Vec3(0.7, 0.52, 0)})
                                 : pieces_of(3, {Vec3(0.3, 0.52, -0.1), Vec3(0.3, 0.52, 0.3), Vec3(0.7, 0.52, -0.1),
                                                 Vec3(0.7, 0.52, 0.3)});
    Mesh mesh = box_mesh(dim, 2, 0.1, {}, Vec3(1, 1, 0.2));
    const Index cells = mesh.cell_count();
    const Index removed = remove_crossed_cells(mesh, pieces);
    EXPECT_GT(removed, 0);
    EXPECT_EQ(mesh.cell_count(), cells - removed);
    for (Index c = 0; c < mesh.cell_count(); ++c)
      for (const CutPiece& p : pieces) EXPECT_FALSE(piece_crosses_cell(mesh, c, p));
    std::vector<char> used(mesh.node_count(), 0);
    for (Index n : mesh.cells) used[n] = 1;
    EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0) << "no orphan node";
  }
}

}  // namespace
}  // namespace kerf
