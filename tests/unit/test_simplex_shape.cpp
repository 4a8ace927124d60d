// Lagrange shape functions on simplices: Kronecker property, partition of
// unity, gradients by finite differences; gmsh node order.
#include <gtest/gtest.h>

#include <cmath>

#include "discretization/fem/simplex_shape.h"
#include "support/test_support.h"

namespace kerf {
namespace {

struct Shape {
  int dim, order;
};

class SimplexShapeTest : public ::testing::TestWithParam<Shape> {};

TEST_P(SimplexShapeTest, KroneckerAndPartitionOfUnity) {
  auto [dim, order] = GetParam();
  int n = simplex_node_count(dim, order);
  std::vector<double> N(n);
  for (int a = 0; a < n; ++a) {
    simplex_shape_values(dim, order, simplex_node_position(dim, order, a), N.data());
    for (int b = 0; b < n; ++b) EXPECT_NEAR(N[b], a == b ? 1.0 : 0.0, 1e-14);
  }
  Vec3 xi(0.21, dim > 1 ? 0.17 : 0.0, dim > 2 ? 0.33 : 0.0);
  simplex_shape_values(dim, order, xi, N.data());
  double sum = 0.0;
  for (double v : N) sum += v;
  EXPECT_NEAR(sum, 1.0, 1e-14);
}

TEST_P(SimplexShapeTest, GradientsMatchFiniteDifferences) {
  auto [dim, order] = GetParam();
  int n = simplex_node_count(dim, order);
  Vec3 xi(0.21, dim > 1 ? 0.17 : 0.0, dim > 2 ? 0.33 : 0.0);
  std::vector<double> dN(n * dim), Np(n), Nm(n);
  simplex_shape_gradients(dim, order, xi, dN.data());
  const double h = 1e-6;
  for (int k = 0; k < dim; ++k) {
    Vec3 p = xi, m = xi;
    p[k] += h;
    m[k] -= h;
    simplex_shape_values(dim, order, p, Np.data());
    simplex_shape_values(dim, order, m, Nm.data());
    for (int a = 0; a < n; ++a) EXPECT_NEAR(dN[a * dim + k], (Np[a] - Nm[a]) / (2 * h), 1e-8);
  }
}

INSTANTIATE_TEST_SUITE_P(AllSimplices, SimplexShapeTest,
                         ::testing::Values(Shape{1, 1}, Shape{1, 2}, Shape{2, 1}, Shape{2, 2}, Shape{3, 1},
                                           Shape{3, 2}));

TEST(SimplexShape, MidEdgeNodesOfGmshMeshesSitOnTheirEdges) {
  for (int dim : {2, 3}) {
    Mesh mesh = testing::unit_box_mesh(dim, 2, 0.5);
    auto edges = mid_edge_corners(dim);
    for (Index c = 0; c < mesh.cell_count(); ++c) {
      auto n = mesh.cell(c);
      EXPECT_GT(cell_measure(mesh, c), 0.0);
      for (std::size_t m = 0; m < edges.size(); ++m) {
        Vec3 mid = 0.5 * (mesh.nodes[n[edges[m][0]]] + mesh.nodes[n[edges[m][1]]]);
        EXPECT_LT((mesh.nodes[n[dim + 1 + m]] - mid).norm(), 1e-12) << "cell " << c << " edge " << m;
      }
    }
  }
}

}  // namespace
}  // namespace kerf
