// Meshless node sets: lattices fitted to the box, graded by refine boxes,
// mesh vertices; nodal volumes add up to the domain; supports follow the local
// spacing; MLS stays invertible and exact across a refinement transition.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "discretization/meshless/mls_shape.h"
#include "discretization/meshless/node_set.h"
#include "discretization/meshless/shape_table.h"
#include "geometry/support_index.h"
#include "support/test_support.h"

namespace kerf {
namespace {

double total(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

TEST(NodeSet, RegularLatticeHasExactVolumesAndSupports) {
  Box box{Vec3(0, 0, 0), Vec3(0.1, 0.02, 0.02)};
  const double h = 0.005;
  NodeSet s = lattice_nodes(3, box, h, {}, 2.2);
  ASSERT_EQ(s.size(), 21 * 5 * 5);
  EXPECT_NEAR(total(s.volume), 0.1 * 0.02 * 0.02, 1e-12 * 4e-5);
  int interior = 0;
  for (Index i = 0; i < s.size(); ++i) {
    EXPECT_NEAR(s.support[i], 2.2 * h, 1e-15);
    if (!s.on_boundary[i]) {
      ++interior;
      EXPECT_NEAR(s.volume[i], h * h * h, 1e-12 * h * h * h);
    }
  }
  EXPECT_EQ(interior, 19 * 3 * 3);
}

TEST(NodeSet, PlaneLatticeHasExactAreas) {
  NodeSet s = lattice_nodes(2, Box{Vec3(0, 0, 0), Vec3(0.1, 0.05, 0)}, 0.01, {}, 2.2);
  ASSERT_EQ(s.size(), 11 * 6);
  EXPECT_NEAR(total(s.volume), 0.005, 1e-15);
  for (Index i = 0; i < s.size(); ++i) EXPECT_EQ(s.positions[i].z(), 0.0);
}

TEST(NodeSet, RefineBoxesGradeTheLatticeAndKeepTheVolume) {
  Box box{Vec3(0, 0, 0), Vec3(0.04, 0.04, 0.04)};
  std::vector<RefineRegion> refine{{Box{Vec3(0.01, 0.01, 0.02), Vec3(0.03, 0.03, 0.04)}, 0.0025}};
  NodeSet coarse = lattice_nodes(3, box, 0.005, {}, 2.2);
  NodeSet graded = lattice_nodes(3, box, 0.005, refine, 2.2);
  EXPECT_GT(graded.size(), coarse.size() + 300);
  EXPECT_NEAR(total(graded.volume), 0.04 * 0.04 * 0.04, 1e-12 * 6.4e-5);
  for (Index i = 0; i < graded.size(); ++i) {
    EXPECT_GT(graded.volume[i], 0.0);
    bool in_region = refine[0].box.contains(graded.positions[i], 1e-12);
    EXPECT_NEAR(graded.support[i], 2.2 * (in_region ? 0.0025 : 0.005), 1e-15) << graded.positions[i].transpose();
  }
  // No node twice.
  SupportIndex index(graded.positions, graded.support);
  std::vector<Index> close;
  for (const Vec3& p : graded.positions) {
    index.within(p, 1e-6, close);
    EXPECT_EQ(close.size(), 1u);
  }
  // MLS is invertible and exact across the transition of spacing.
  NeighborLists lists;
  std::vector<Vec3> samples;
  for (double x = 0.004; x < 0.036; x += 0.0031) samples.emplace_back(x, 0.02, 0.019);
  lists = covering_supports(index, samples);
  for (Index q = 0; q < lists.size(); ++q) {
    std::vector<Vec3> nodes;
    std::vector<double> radii;
    for (Index i : lists.of(q)) nodes.push_back(graded.positions[i]), radii.push_back(graded.support[i]);
    MlsShape shape;
    ASSERT_TRUE(mls_shape_functions(3, MlsBasis::linear, samples[q], nodes, radii, false, shape))
        << samples[q].transpose() << " condition " << shape.condition;
    Vec3 reproduced = Vec3::Zero();
    for (std::size_t I = 0; I < nodes.size(); ++I) reproduced += shape.value[I] * nodes[I];
    EXPECT_LT((reproduced - samples[q]).norm(), 1e-12);
  }
}

TEST(NodeSet, MeshNodesAreTheCornersWithTheMeshVolume) {
  Mesh mesh = testing::unit_box_mesh(3, 2, 0.3);
  NodeSet s = mesh_nodes(mesh, 2.2);
  EXPECT_LT(s.size(), mesh.node_count());  // mid-edge nodes are left out
  EXPECT_NEAR(total(s.volume), 1.0, 1e-12);
  for (Index i = 0; i < s.size(); ++i) {
    EXPECT_GT(s.spacing[i], 0.05);
    EXPECT_LT(s.spacing[i], 0.6);
    const Vec3& p = s.positions[i];
    bool on_face = (p.array() < 1e-12).any() || (p.array() > 1 - 1e-12).any();
    EXPECT_EQ(static_cast<bool>(s.on_boundary[i]), on_face) << p.transpose();
  }
}

// A mesh node's spacing is that of a lattice as dense: over the interior
// nodes, spacing^d averages the nodal volume (a lattice's interior node holds
// h^d), also on a graded mesh, so `support` covers as many nodes on a mesh as
// on a lattice (the mean edge length alone made supports 1.12 times as wide
// on gmsh tets: 1.4 times the neighbours).
TEST(NodeSet, MeshNodeSpacingIsTheEquivalentLatticeSpacing) {
  for (int dim : {2, 3}) {
    const Mesh mesh = testing::unit_box_mesh(dim, 1, dim == 3 ? 0.1 : 0.04);
    const NodeSet s = mesh_nodes(mesh, 2.2);
    double spacing_power = 0.0, volume = 0.0;
    for (Index i = 0; i < s.size(); ++i) {
      if (s.on_boundary[i]) continue;
      spacing_power += std::pow(s.spacing[i], dim);
      volume += s.volume[i];
      EXPECT_DOUBLE_EQ(s.support[i], 2.2 * s.spacing[i]);
    }
    EXPECT_NEAR(spacing_power / volume, 1.0, 0.05) << dim << "D";
  }
}

// covering_supports finds a group of close queries' candidates once, around
// the group: each query's list must be the one its own search gives, on
// supports of three octaves, for groups as tight as a cell's Gauss points and
// as loose as a row of points across the box, and for a last group cut short.
TEST(SupportIndex, GroupsOfQueriesShareASearchAndGetTheirOwnLists) {
  std::srand(3);
  std::vector<Vec3> positions;
  std::vector<double> radius;
  for (int i = 0; i < 1500; ++i) {
    positions.emplace_back(Vec3::Random() * 0.02);
    radius.push_back(0.003 * std::pow(2.0, (std::rand() % 300) / 100.0));
  }
  const SupportIndex index(positions, radius);
  std::vector<Vec3> queries;
  for (int g = 0; g < 50; ++g) {
    const Vec3 centre = Vec3::Random() * 0.025;  // some past the nodes' box
    for (int k = 0; k < 14; ++k) queries.push_back(centre + Vec3::Random() * (g % 5 == 0 ? 0.02 : 0.001));
  }
  queries.resize(queries.size() - 5);
  std::vector<Index> own;
  for (Index group : {1, 4, 14, 100}) {
    const NeighborLists lists = covering_supports(index, queries, group);
    ASSERT_EQ(lists.size(), static_cast<Index>(queries.size()));
    Index reached = 0;
    for (Index q = 0; q < lists.size(); ++q) {
      index.reaching(queries[q], 0.0, own);
      const auto list = lists.of(q);
      EXPECT_EQ(std::vector<Index>(list.begin(), list.end()), own) << "group " << group << " query " << q;
      reached += static_cast<Index>(own.size());
    }
    EXPECT_GT(reached, 10 * lists.size()) << group;
  }
}

// A table's values and gradients are not zeroed before its rows are filled:
// every entry must be written, a singular row counted as zeros. The heap is
// first filled with NaN where a table of this size lands (a freed block of
// the same size), so an entry left unwritten shows.
TEST(ShapeTable, EveryEntryIsWrittenAndASingularRowCountedIsZero) {
  const NodeSet nodes = lattice_nodes(2, Box{Vec3(0, 0, 0), Vec3(0.02, 0.01, 0)}, 0.002, {}, 2.2);
  const SupportIndex index(nodes.positions, nodes.support);
  std::vector<Vec3> points;
  for (double x = 0.0005; x < 0.02; x += 0.0017) points.emplace_back(x, 0.0043, 0.0);
  points.emplace_back(0.02 + 0.0041, 0.005, 0.0);  // beyond the plate's edge: one column of nodes, collinear
  std::size_t slots = 0;
  for (const Vec3& x : points) {
    std::vector<Index> near;
    index.reaching(x, 0.0, near);
    slots += near.size();
  }
  for (int round = 0; round < 3; ++round) {
    std::vector<double>(3 * slots, std::numeric_limits<double>::quiet_NaN());  // freed at once
    std::vector<double>(slots, std::numeric_limits<double>::quiet_NaN());
    Index singular = 0;
    const ShapeTable t = shape_table(nodes, index, MlsBasis::linear, points, "the point", "", "", nullptr, false,
                                     &singular, 4);
    ASSERT_EQ(singular, 1);
    for (Index p = 0; p < t.point_count(); ++p) {
      double sum = 0.0;
      Vec3 gradient_sum = Vec3::Zero();
      for (Index k = 0; k < static_cast<Index>(t.neighbours.of(p).size()); ++k) {
        sum += t.values_of(p)[k];
        gradient_sum += Vec3(t.gradients_of(p)[2 * k], t.gradients_of(p)[2 * k + 1], 0.0);
      }
      const bool last = p + 1 == t.point_count();  // the singular one: zeros
      EXPECT_NEAR(sum, last ? 0.0 : 1.0, 1e-12) << "point " << p;
      EXPECT_LT(gradient_sum.norm(), 1e-8) << "point " << p;
      if (last) {
        for (Index k = 0; k < static_cast<Index>(t.neighbours.of(p).size()); ++k) EXPECT_EQ(t.values_of(p)[k], 0.0);
      }
    }
  }
}

}  // namespace
}  // namespace kerf
