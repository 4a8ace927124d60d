// The background cells made on a node lattice without a mesher
// (geometry/lattice_cells.h): they fill the box, are positively oriented,
// meet face to face, and their nodes are the meshless lattice's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include "discretization/meshless/node_set.h"
#include "geometry/boundary_facets.h"
#include "geometry/lattice_cells.h"
#include "geometry/mid_edge_nodes.h"

namespace kerf {
namespace {

/// Is every node of the facet on one face of the box (one coordinate at its min or max)?
bool on_one_box_face(const Mesh& mesh, std::span<const Index> facet, const Vec3& min, const Vec3& max) {
  for (int a = 0; a < mesh.dimension; ++a)
    for (double plane : {min[a], max[a]}) {
      const bool all = std::all_of(facet.begin(), facet.end(),
                                   [&](Index n) { return std::abs(mesh.nodes[n][a] - plane) < 1e-12; });
      if (all) return true;
    }
  return false;
}

/// Each facet (sorted corners) and how many cells hold it.
std::map<std::vector<Index>, int> facet_use(const Mesh& mesh) {
  std::map<std::vector<Index>, int> use;
  const int corners = mesh.dimension + 1;
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    auto cell = mesh.cell(c);
    for (int skip = 0; skip < corners; ++skip) {
      std::vector<Index> facet;
      for (int k = 0; k < corners; ++k)
        if (k != skip) facet.push_back(cell[k]);
      std::sort(facet.begin(), facet.end());
      ++use[facet];
    }
  }
  return use;
}

void expect_cells_fill_the_box_face_to_face(int dim, const Vec3& min, const Vec3& max, double spacing) {
  const Mesh mesh = lattice_cells(dim, min, max, spacing);
  const std::array<int, 3> n = lattice_intervals(dim, min, max, spacing);
  ASSERT_EQ(mesh.cell_count(), static_cast<Index>(lattice_cell_count(dim, n)));
  ASSERT_EQ(mesh.node_count(), (n[0] + 1) * (n[1] + 1) * (dim == 3 ? n[2] + 1 : 1));

  double measure = 0.0, box = 1.0, smallest = INFINITY;
  for (int a = 0; a < dim; ++a) box *= max[a] - min[a];
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    smallest = std::min(smallest, cell_measure(mesh, c));
    measure += cell_measure(mesh, c);
  }
  // A cube's corner tets hold a sixth of it each, the central one a third; a square's triangles half of it.
  const double cube = box / (n[0] * n[1] * (dim == 3 ? n[2] : 1));
  EXPECT_NEAR(smallest, cube / (dim == 3 ? 6.0 : 2.0), 1e-9 * cube);
  EXPECT_NEAR(measure, box, 1e-12 * box);

  // Face to face: each facet held by two cells, or by one on the box's boundary, and then by as many as the
  // boundary's squares (2D: edges) split in two (3D) or not (2D).
  int boundary = 0;
  for (const auto& [facet, cells] : facet_use(mesh)) {
    ASSERT_TRUE(cells == 1 || cells == 2) << cells << " cells hold one facet";
    if (cells == 1) {
      ++boundary;
      EXPECT_TRUE(on_one_box_face(mesh, facet, min, max)) << "a facet of one cell inside the box";
    }
  }
  const int expected = dim == 3 ? 2 * 2 * (n[0] * n[1] + n[1] * n[2] + n[0] * n[2]) : 2 * (n[0] + n[1]);
  EXPECT_EQ(boundary, expected);
  EXPECT_EQ(boundary_facets(mesh).count(), expected);

  // The same points as the meshless lattice's nodes, to the bit.
  const NodeSet lattice = lattice_nodes(dim, Box{min, max}, spacing, {}, 2.2);
  ASSERT_EQ(lattice.size(), mesh.node_count());
  auto key = [](const Vec3& p) { return std::array<double, 3>{p.x(), p.y(), p.z()}; };
  std::set<std::array<double, 3>> nodes;
  for (const Vec3& p : lattice.positions) nodes.insert(key(p));
  for (const Vec3& p : mesh.nodes) EXPECT_TRUE(nodes.count(key(p))) << p.transpose();
}

TEST(LatticeCells, FillAnUnevenBoxFaceToFaceOnTheMeshlessLattice) {
  // Intervals 14 x 4 x 4 of unequal lengths (0.1 / 0.007, 0.03 / 0.007 rounded), odd and even counts.
  expect_cells_fill_the_box_face_to_face(3, Vec3(0.0, 0.0, -0.01), Vec3(0.1, 0.03, 0.02), 0.007);
  expect_cells_fill_the_box_face_to_face(3, Vec3(-1.0, 2.0, 0.5), Vec3(0.5, 3.1, 1.4), 0.3);
  expect_cells_fill_the_box_face_to_face(2, Vec3(0.0, -0.02, 0.0), Vec3(0.05, 0.03, 0.0), 0.004);
}

TEST(LatticeCells, AThinBoxKeepsOneLayer) {
  // Thinner than the spacing along z: one interval there (as lattice_nodes places its nodes).
  expect_cells_fill_the_box_face_to_face(3, Vec3(0.0, 0.0, 0.0), Vec3(0.05, 0.02, 0.001), 0.005);
}

TEST(LatticeCells, RaisedToSecondOrderTheyHaveOneMidEdgeNodeAnEdgeAsTheEstimateCounts) {
  // fem.box_mesher: lattice with tet10 or tri6: a node at the middle of each of the cells' edges, once.
  for (const auto& [dim, max, spacing] : {std::tuple<int, Vec3, double>{3, Vec3(0.1, 0.03, 0.02), 0.007},
                                          {3, Vec3(0.05, 0.02, 0.001), 0.005},
                                          {2, Vec3(0.05, 0.03, 0.0), 0.004}}) {
    const Mesh linear = lattice_cells(dim, Vec3::Zero(), max, spacing);
    const Mesh raised = with_mid_edge_nodes(linear);
    const std::array<int, 3> n = lattice_intervals(dim, Vec3::Zero(), max, spacing);
    EXPECT_EQ(raised.order, 2);
    ASSERT_EQ(raised.cell_count(), linear.cell_count());
    std::set<std::pair<Index, Index>> edges;
    const auto pairs = mid_edge_corners(dim);
    for (Index c = 0; c < raised.cell_count(); ++c) {
      auto cell = raised.cell(c), corners = linear.cell(c);
      for (int k = 0; k <= dim; ++k) ASSERT_EQ(cell[k], corners[k]);
      for (std::size_t e = 0; e < pairs.size(); ++e) {
        const Index a = cell[pairs[e][0]], b = cell[pairs[e][1]], middle = cell[dim + 1 + e];
        EXPECT_LT((raised.nodes[middle] - 0.5 * (raised.nodes[a] + raised.nodes[b])).norm(), 1e-15);
        edges.insert({std::min(a, b), std::max(a, b)});
      }
    }
    EXPECT_EQ(static_cast<double>(edges.size()), lattice_edge_count(dim, n));
    EXPECT_EQ(raised.node_count(), linear.node_count() + static_cast<Index>(lattice_edge_count(dim, n)));
  }
}

}  // namespace
}  // namespace kerf
