// Geometry pieces on real gmsh meshes: orientation, boundary facets, colouring,
// locality ordering, point location, refine boxes, and gmsh leaving kerf's
// OpenMP thread count alone.
#include <gtest/gtest.h>

#include <random>
#include <omp.h>

#include <set>

#include "core/threads_worth_waking.h"
#include "geometry/box_mesher.h"
#include "geometry/cell_coloring.h"
#include "geometry/cell_schedule.h"
#include "geometry/mesh_ordering.h"
#include "geometry/point_location.h"
#include "support/test_support.h"

namespace kerf {
namespace {

double total_measure(const Mesh& mesh) {
  double v = 0.0;
  for (Index c = 0; c < mesh.cell_count(); ++c) v += cell_measure(mesh, c);
  return v;
}

TEST(Geometry, GmshLeavesTheOpenMpThreadCountAlone) {
  omp_set_num_threads(2);
  testing::unit_box_mesh(3, 1, 0.5);
  EXPECT_EQ(omp_get_max_threads(), 2);
}

TEST(Geometry, MeshingIsDeterministic) {
  omp_set_num_threads(2);
  Mesh first = testing::unit_box_mesh(3, 2, 0.2);
  for (int repeat = 0; repeat < 3; ++repeat) {
    Mesh again = testing::unit_box_mesh(3, 2, 0.2);
    ASSERT_EQ(again.cells, first.cells);
    ASSERT_EQ(again.nodes.size(), first.nodes.size());
    for (std::size_t i = 0; i < first.nodes.size(); ++i) ASSERT_EQ(again.nodes[i], first.nodes[i]);
  }
}

TEST(Geometry, BoxMeshesArePositiveAndFillTheBox) {
  for (int dim : {2, 3})
    for (int order : {1, 2}) {
      Mesh mesh = testing::unit_box_mesh(dim, order, 0.3);
      for (Index c = 0; c < mesh.cell_count(); ++c) ASSERT_GT(cell_measure(mesh, c), 0.0);
      EXPECT_NEAR(total_measure(mesh), 1.0, 1e-12) << dim << "D order " << order;
    }
}

TEST(Geometry, BoundaryFacetsCoverTheSurfaceWithOutwardNormals) {
  Mesh mesh = testing::unit_box_mesh(3, 1, 0.3);
  BoundaryFacets facets = boundary_facets(mesh);
  double area = 0.0;
  for (Index f = 0; f < facets.count(); ++f) {
    auto n = facets.facet(f);
    Vec3 a = mesh.nodes[n[0]], b = mesh.nodes[n[1]], c = mesh.nodes[n[2]];
    Vec3 normal = 0.5 * (b - a).cross(c - a);
    area += normal.norm();
    // Outward: the normal points away from the box centre.
    Vec3 centre = (a + b + c) / 3.0;
    EXPECT_GT(normal.dot(centre - Vec3(0.5, 0.5, 0.5)), 0.0);
  }
  EXPECT_NEAR(area, 6.0, 1e-12);
}

// Each node's neighbours are the other nodes of its cells, ascending, each
// once: against sets built cell by cell on a gmsh box (tet10: mid-edge nodes too).
TEST(Geometry, NodeAdjacencyListsEachNeighbourOnceInOrder) {
  const Mesh mesh = testing::unit_box_mesh(3, 2, 0.5);
  std::vector<std::set<Index>> expected(static_cast<std::size_t>(mesh.node_count()));
  for (Index c = 0; c < mesh.cell_count(); ++c)
    for (Index a : mesh.cell(c))
      for (Index b : mesh.cell(c))
        if (a != b) expected[a].insert(b);
  std::vector<Index> start, adjacent;
  node_adjacency(mesh, start, adjacent);
  ASSERT_EQ(start.size(), static_cast<std::size_t>(mesh.node_count()) + 1);
  for (Index n = 0; n < mesh.node_count(); ++n)
    EXPECT_EQ(std::vector<Index>(adjacent.begin() + start[n], adjacent.begin() + start[n + 1]),
              std::vector<Index>(expected[n].begin(), expected[n].end()))
        << "node " << n;
}

TEST(Geometry, CellsOfOneColourShareNoNode) {
  Mesh mesh = testing::unit_box_mesh(3, 2, 0.25);
  CellColoring coloring = color_cells(mesh);
  EXPECT_EQ(static_cast<Index>(coloring.cells.size()), mesh.cell_count());
  std::set<Index> every(coloring.cells.begin(), coloring.cells.end());
  EXPECT_EQ(static_cast<Index>(every.size()), mesh.cell_count());
  for (int k = 0; k < coloring.color_count(); ++k) {
    std::set<Index> nodes;
    for (Index i = coloring.start[k]; i < coloring.start[k + 1]; ++i)
      for (Index n : mesh.cell(coloring.cells[i])) ASSERT_TRUE(nodes.insert(n).second) << "colour " << k;
  }
}

/// Every cell of [begin, end) (all by default) once, none outside; the ranges of a phase share no node.
void expect_conflict_free_cover(const Mesh& mesh, const CellSchedule& s, Index begin = 0, Index end = -1) {
  if (end < 0) end = mesh.cell_count();
  std::vector<int> seen(mesh.cell_count(), 0);
  for (const auto& phase : s.phases) {
    std::vector<int> owner(mesh.nodes.size(), -1);
    for (std::size_t r = 0; r < phase.size(); ++r)
      for (Index k = phase[r].first; k < phase[r].second; ++k) {
        ++seen[s.cells[k]];
        for (Index n : mesh.cell(s.cells[k])) {
          ASSERT_TRUE(owner[n] < 0 || owner[n] == static_cast<int>(r)) << "two ranges of a phase share node " << n;
          owner[n] = static_cast<int>(r);
        }
      }
  }
  for (Index c = 0; c < mesh.cell_count(); ++c) ASSERT_EQ(seen[c], c >= begin && c < end ? 1 : 0) << "cell " << c;
}

TEST(Geometry, CellScheduleIsBandedOnOrderedMeshesAndColouredOtherwise) {
  Mesh mesh = testing::unit_box_mesh(3, 1, 0.08);
  CellSchedule unordered = schedule_cells(mesh, 2);
  expect_conflict_free_cover(mesh, unordered);
  order_for_locality(mesh);
  CellSchedule banded = schedule_cells(mesh, 2);
  EXPECT_TRUE(banded.banded);
  EXPECT_EQ(banded.phases.size(), 2u);
  expect_conflict_free_cover(mesh, banded);
  // Too many threads for the band: the chunks touch, so colours take over.
  CellSchedule many = schedule_cells(mesh, 64);
  EXPECT_FALSE(many.banded);
  expect_conflict_free_cover(mesh, many);
}

// A rank's share of the cells (a range of the ordered mesh) is scheduled
// alone, banded or by colours.
TEST(Geometry, CellScheduleOfARangeCoversThatRangeOnly) {
  Mesh mesh = testing::unit_box_mesh(3, 1, 0.08);
  order_for_locality(mesh);
  const Index begin = mesh.cell_count() / 3, end = 2 * mesh.cell_count() / 3;
  expect_conflict_free_cover(mesh, schedule_cells(mesh, 2, begin, end), begin, end);
  CellSchedule many = schedule_cells(mesh, 64, begin, end);
  EXPECT_FALSE(many.banded);
  expect_conflict_free_cover(mesh, many, begin, end);
  expect_conflict_free_cover(mesh, schedule_cells(mesh, 1, begin, end), begin, end);
}

// Threads sleep when they wait: a phase whose share a thread is small runs on
// one thread (core/threads_worth_waking.h), every cell still covered once.
TEST(Geometry, CellScheduleTakesOneThreadWhereAThreadsShareIsTooSmallToWakeIt) {
  const int kept = omp_get_max_threads();
  omp_set_num_threads(2);
  Mesh small = testing::unit_box_mesh(3, 1, 0.25);  // a few hundred cells
  order_for_locality(small);
  ASSERT_LT(small.cell_count(), 2 * items_worth_a_thread);
  const CellSchedule one = schedule_cells_worth_threads(small, 0, small.cell_count());
  EXPECT_EQ(one.threads, 1);
  EXPECT_EQ(one.phases.size(), 1u);
  expect_conflict_free_cover(small, one);
  Mesh large = testing::unit_box_mesh(3, 1, 0.08);  // banded: two phases of a chunk a thread
  order_for_locality(large);
  const CellSchedule two = schedule_cells_worth_threads(large, 0, large.cell_count());
  ASSERT_TRUE(two.banded) << large.cell_count() << " cells";
  EXPECT_EQ(two.threads, 2);
  expect_conflict_free_cover(large, two);
  // Coloured, the same cells make phases too thin a thread: one thread.
  Mesh shuffled = testing::unit_box_mesh(3, 1, 0.08);
  const CellSchedule coloured = schedule_cells(shuffled, 2);
  ASSERT_FALSE(coloured.banded);
  const Index share = shuffled.cell_count() / (2 * static_cast<Index>(coloured.phases.size()));
  ASSERT_LT(share, items_worth_a_thread) << coloured.phases.size() << " colours";
  const CellSchedule thin = schedule_cells_worth_threads(shuffled, 0, shuffled.cell_count());
  EXPECT_EQ(thin.threads, 1);
  expect_conflict_free_cover(shuffled, thin);
  omp_set_num_threads(kept);
}

TEST(Geometry, LocalityOrderingKeepsTheMeshAndNarrowsTheBandwidth) {
  Mesh mesh = testing::unit_box_mesh(3, 1, 0.15);
  auto bandwidth = [](const Mesh& m) {
    Index widest = 0;
    for (Index c = 0; c < m.cell_count(); ++c) {
      auto n = m.cell(c);
      widest = std::max(widest, *std::max_element(n.begin(), n.end()) - *std::min_element(n.begin(), n.end()));
    }
    return widest;
  };
  Mesh ordered = mesh;
  order_for_locality(ordered);
  EXPECT_NEAR(total_measure(ordered), total_measure(mesh), 1e-12);
  for (Index c = 0; c < ordered.cell_count(); ++c) ASSERT_GT(cell_measure(ordered, c), 0.0);
  EXPECT_LT(bandwidth(ordered), bandwidth(mesh) / 2);
}

TEST(Geometry, PointLocationFindsTheCellAndItsReferenceCoordinates) {
  Mesh mesh = testing::unit_box_mesh(3, 1, 0.3);
  for (const Vec3& x : {Vec3(0.31, 0.52, 0.77), Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(0.5, 0.0, 0.5)}) {
    auto at = locate_point(mesh, x, 1e-9);
    ASSERT_TRUE(at) << x.transpose();
    auto n = mesh.cell(at->cell);
    const Vec3& xi = at->local;
    Vec3 back = (1 - xi.sum()) * mesh.nodes[n[0]] + xi.x() * mesh.nodes[n[1]] + xi.y() * mesh.nodes[n[2]] +
                xi.z() * mesh.nodes[n[3]];
    EXPECT_LT((back - x).norm(), 1e-12);
  }
  EXPECT_FALSE(locate_point(mesh, Vec3(1.1, 0.5, 0.5), 1e-3));
  EXPECT_TRUE(locate_point(mesh, Vec3(1.0005, 0.5, 0.5), 1e-3));
}

TEST(Geometry, CellLocatorGivesTheSameCellsAsTheFullSearch) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-0.05, 1.05);
  for (int dim : {2, 3}) {
    Mesh mesh = testing::unit_box_mesh(dim, 1, 0.15);
    CellLocator locator(mesh);
    for (int i = 0; i < 300; ++i) {
      Vec3 x(coordinate(random), coordinate(random), dim == 3 ? coordinate(random) : 0.0);
      if (i < 20) x = mesh.nodes[i];  // on shared corners: the lowest-numbered cell, both ways
      auto full = locate_point(mesh, x, 0.02), binned = locator.locate(mesh, x, 0.02);
      ASSERT_EQ(full.has_value(), binned.has_value()) << x.transpose();
      if (!full) continue;
      EXPECT_EQ(full->cell, binned->cell) << x.transpose();
      EXPECT_LT((full->local - binned->local).norm(), 1e-12);
    }
  }
}

TEST(Geometry, RefineBoxesMakeTheMeshFinerWhereAsked) {
  BoxMeshRequest coarse;
  coarse.min = Vec3::Zero();
  coarse.max = Vec3::Ones();
  coarse.size = 0.25;
  BoxMeshRequest refined = coarse;
  refined.refine.push_back({Vec3(0, 0, 0.8), Vec3(1, 1, 1), 0.06});
  Mesh a = mesh_box(coarse), b = mesh_box(refined);
  auto nodes_in_top = [](const Mesh& m) {
    return std::count_if(m.nodes.begin(), m.nodes.end(), [](const Vec3& p) { return p.z() > 0.8; });
  };
  EXPECT_GT(nodes_in_top(b), 5 * nodes_in_top(a));
  EXPECT_NEAR(total_measure(b), 1.0, 1e-12);
}

}  // namespace
}  // namespace kerf
