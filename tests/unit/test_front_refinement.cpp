// fem.split_front: subdivide (discretization/fem/front_refinement.h) on real
// gmsh meshes: the refined mesh is conforming (every face in one or two
// cells, the same boundary area), keeps the volume and the orientation, and
// makes the front a chain of edges; after the split every cell the cut meets
// is separated behind the front and whole beyond it (no lag); quadratic
// children sit on their parent's map; the degenerate placements (a front
// through a node, along an edge) stay conforming.
#include <gtest/gtest.h>

#include <map>

#include "discretization/fem/front_refinement.h"
#include "discretization/fem/simplex_shape.h"
#include "geometry/cell_split.h"
#include "support/cut_geometry.h"
#include "support/test_support.h"

namespace kerf {
namespace {

/// The plane n . x = d above the front z = front (2D: the line above y = front).
struct FrontCut {
  Vec3 n;
  double d, front;
  std::vector<CutPiece> pieces(int dim) const { return testing::plane_cut_above(dim, n, d, front); }
  double phi(const Vec3& x) const { return n.dot(x) - d; }
  double height(const Vec3& x, int dim) const { return dim == 3 ? x.z() : x.y(); }
};

std::vector<Index> sorted_corners(const Mesh& m, Index c, int skip) {
  std::vector<Index> f;
  for (int k = 0; k <= m.dimension; ++k)
    if (k != skip) f.push_back(m.cell(c)[k]);
  std::sort(f.begin(), f.end());
  return f;
}

/// Every facet in one or two cells; returns the boundary's measure.
double expect_conforming(const Mesh& m) {
  std::map<std::vector<Index>, int> uses;
  for (Index c = 0; c < m.cell_count(); ++c)
    for (int k = 0; k <= m.dimension; ++k) ++uses[sorted_corners(m, c, k)];
  double boundary = 0.0;
  int bad = 0;
  for (const auto& [facet, n] : uses) {
    bad += n > 2;
    if (n != 1) continue;
    const Vec3 &a = m.nodes[facet[0]], &b = m.nodes[facet[1]];
    boundary += m.dimension == 3 ? 0.5 * (b - a).cross(m.nodes[facet[2]] - a).norm() : (b - a).norm();
  }
  EXPECT_EQ(bad, 0) << "facets in more than two cells";
  return boundary;
}

double total_measure(const Mesh& m) {
  double v = 0.0;
  for (Index c = 0; c < m.cell_count(); ++c) {
    EXPECT_GT(cell_measure(m, c), 0.0) << "cell " << c;
    v += cell_measure(m, c);
  }
  return v;
}

struct Case {
  int dim, order;
  double size;
};

class FrontRefinementTest : public ::testing::TestWithParam<Case> {};

TEST_P(FrontRefinementTest, IsConformingKeepsTheVolumeAndMakesTheFrontEdges) {
  const Case c = GetParam();
  const Mesh mesh = testing::unit_box_mesh(c.dim, c.order, c.size);
  const FrontCut cut{c.dim == 3 ? Vec3(1, 0.3, 0.2) : Vec3(1, 0.3, 0), 0.6, 0.43};
  const FrontRefinement r = refine_front(mesh, cut.pieces(c.dim));
  ASSERT_GT(r.subdivided_cells, 0);
  ASSERT_GT(r.front_segments, c.dim == 3 ? 3 : -1);
  EXPECT_EQ(r.unresolved_segments, 0);
  EXPECT_NEAR(total_measure(r.mesh), total_measure(mesh), 1e-12);
  EXPECT_NEAR(expect_conforming(r.mesh), expect_conforming(mesh), 1e-12);
  // Input nodes keep their place; every node is some cell's.
  std::vector<char> used(r.mesh.node_count(), 0);
  for (Index n : r.mesh.cells) used[n] = 1;
  for (Index n = 0; n < r.mesh.node_count(); ++n) {
    EXPECT_TRUE(used[n]) << "node " << n;
    if (r.input_node[n] >= 0) {
      EXPECT_EQ(r.mesh.nodes[n], mesh.nodes[r.input_node[n]]);
    }
  }
  // Children's nodes sit where their parent's map puts their reference coordinates.
  const int npc = mesh.nodes_per_cell();
  std::vector<double> N(npc);
  for (Index k = 0; k < r.mesh.cell_count(); ++k) {
    if (!r.child(k)) continue;
    for (int a = 0; a < npc; ++a) {
      simplex_shape_values(c.dim, c.order, r.child_reference(k)[a], N.data());
      Vec3 x = Vec3::Zero();
      for (int b = 0; b < npc; ++b) x += N[b] * mesh.nodes[mesh.cell(r.parent[k])[b]];
      EXPECT_LT((x - r.mesh.nodes[r.mesh.cell(k)[a]]).norm(), 1e-14) << "child " << k << " node " << a;
    }
  }
}

/// The cells the cut's plane crosses inside, after the front refinement and
/// the split: those whose crossing lies behind the front (above it by more
/// than round-off) that are not separated, and those beyond it (below by more
/// than round-off) that are; `behind` counts the first kind's cells.
int misplaced_copies(const Case& c, int* behind) {
  const Mesh mesh = testing::unit_box_mesh(c.dim, c.order, c.size);
  const FrontCut cut{c.dim == 3 ? Vec3(1, 0.3, 0.2) : Vec3(1, 0.3, 0), 0.6, 0.43};
  const auto pieces = cut.pieces(c.dim);
  const FrontRefinement r = refine_front(mesh, pieces);
  const CellSplit split = split_cells(r.mesh, pieces, {.snap = 0.0, .min_fraction = 0.0});
  std::vector<int> copies(r.mesh.cell_count(), 0);
  for (Index p : split.parent) ++copies[p];
  const double tol = 1e-9;
  int wrong = 0;
  *behind = 0;
  for (Index k = 0; k < r.mesh.cell_count(); ++k) {
    const auto cell = r.mesh.cell(k);
    double lowest = 1e9, highest = -1e9;
    for (int i = 0; i <= c.dim; ++i)
      for (int j = i + 1; j <= c.dim; ++j) {
        const Vec3 &a = r.mesh.nodes[cell[i]], &b = r.mesh.nodes[cell[j]];
        const double pa = cut.phi(a), pb = cut.phi(b);
        if (!((pa > tol && pb < -tol) || (pa < -tol && pb > tol))) continue;
        const double h = cut.height(a + pa / (pa - pb) * (b - a), c.dim);
        lowest = std::min(lowest, h), highest = std::max(highest, h);
      }
    if (highest < lowest) continue;  // the plane does not cross it inside
    if (lowest > cut.front + tol) {
      ++*behind;
      wrong += copies[k] != 2;
    } else if (highest < cut.front - tol) {
      wrong += copies[k] != 1;
    } else {
      ADD_FAILURE() << "cell " << k << " has the front inside";
    }
  }
  return wrong;
}

// After the split, every cell the cut's plane crosses inside is separated
// where the crossing lies behind the front and whole where it lies beyond:
// the jump ends on the front. (The split's snap, 0 here, puts nodes near the
// cut on it, and cells crossed only near those rightly stay whole.)
TEST_P(FrontRefinementTest, TheSplitThatFollowsEndsOnTheFront) {
  int behind = 0;
  EXPECT_EQ(misplaced_copies(GetParam(), &behind), 0);
  EXPECT_GT(behind, 10);
}

// Degenerate placements on Kuhn cubes, whose lattice planes hold nodes and
// edges: a front along mesh edges through nodes (the plane x = 0.5 above z =
// 0.5: it inserts nothing, the front already is edges), and a front lying in
// a lattice plane of faces while crossing the others at their edges (x + 0.3 y
// = 0.6 above z = 0.5: edge points only). Each stays conforming, keeps the
// volume and makes the front edges, its points on the front line.
TEST(FrontRefinement, DegeneratePlacementsStayConformingAndEndOnTheFront) {
  const Mesh mesh = testing::kuhn_cubes(4, 0.25);
  for (const FrontCut& cut : {FrontCut{Vec3(1, 0, 0), 0.5, 0.5}, FrontCut{Vec3(1, 0.3, 0), 0.6, 0.5}}) {
    const FrontRefinement r = refine_front(mesh, cut.pieces(3));
    EXPECT_GT(r.front_segments, 3);
    EXPECT_EQ(r.unresolved_segments, 0);
    EXPECT_NEAR(total_measure(r.mesh), total_measure(mesh), 1e-12);
    EXPECT_NEAR(expect_conforming(r.mesh), expect_conforming(mesh), 1e-12);
    for (std::size_t p = 0; p < r.mesh.nodes.size(); ++p)
      if (r.input_node[p] < 0) {  // an inserted point lies on the front line
        EXPECT_NEAR(r.mesh.nodes[p].z(), 0.5, 1e-12);
        EXPECT_NEAR(cut.phi(r.mesh.nodes[p]), 0.0, 1e-12);
      }
    if (cut.n.y() == 0) EXPECT_EQ(r.subdivided_cells, 0) << "the front already runs along edges";
    else EXPECT_GT(r.subdivided_cells, 0);
  }
}

const Case cases[] = {{3, 1, 0.21}, {3, 2, 0.21}, {3, 1, 0.13}, {2, 1, 0.13}, {2, 2, 0.13}};
INSTANTIATE_TEST_SUITE_P(Meshes, FrontRefinementTest, ::testing::ValuesIn(cases), [](const auto& info) {
  const Case& c = info.param;
  return std::string(c.dim == 3 ? "tet" : "tri") + std::to_string(c.order == 1 ? c.dim + 1 : (c.dim == 3 ? 10 : 6)) +
         "_h" + std::to_string(static_cast<int>(c.size * 100));
});

}  // namespace
}  // namespace kerf
